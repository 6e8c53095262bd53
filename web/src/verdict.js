// The report's verdict: the worst of its items, the limits reached or exceeded and the warnings, so that the
// page never shows a clean bill beside something that needs a look.

/** Severities from harmless to worst; the verdict's level is one of them. */
export const LEVELS = ['ok', 'warning', 'reached', 'exceeded'];

const TEXT = {
  ok: 'No limit reached, no warning',
  warning: 'Warnings to check',
  reached: 'Limit reached',
  exceeded: 'Limit exceeded',
};

/** "2 limits · 1 warning" */
function counts(limits, warnings) {
  const parts = [];
  if (limits) parts.push(`${limits} limit${limits === 1 ? '' : 's'}`);
  if (warnings) parts.push(`${warnings} warning${warnings === 1 ? '' : 's'}`);
  return parts.join(' · ');
}

/**
 * {level, text, items}: the items (limits with severity "reached" or "exceeded", warnings with "warning"),
 * worst first, and the level of the worst of them ("ok" without any).
 */
export function verdictOf(data) {
  const limits = data.limits_reached.map((l) => ({ ...l, severity: l.severity === 'exceeded' ? 'exceeded' : 'reached' }));
  const warnings = data.warnings.map((w) => ({ ...w, severity: 'warning' }));
  const items = [...limits, ...warnings].sort((a, b) => LEVELS.indexOf(b.severity) - LEVELS.indexOf(a.severity));
  const level = items.length ? items[0].severity : 'ok';
  const text = level === 'ok' ? TEXT.ok : `${TEXT[level]} · ${counts(limits.length, warnings.length)}`;
  return { level, text, items };
}
