// Whether a canvas has drawn anything, for the browser test's hooks. The canvas is copied into one kept for
// reading back rather than read itself: Chromium warns on the console when a canvas without
// willReadFrequently is read more than once, and the plots' canvases are uPlot's.

let scratch = null;

/** True when some pixel of canvas `c` is not transparent. */
export function painted(c) {
  if (!c || !c.width || !c.height) return false;
  scratch = scratch || document.createElement('canvas');
  scratch.width = c.width;
  scratch.height = c.height;
  const ctx = scratch.getContext('2d', { willReadFrequently: true });
  ctx.clearRect(0, 0, c.width, c.height);
  ctx.drawImage(c, 0, 0);
  const px = ctx.getImageData(0, 0, c.width, c.height).data;
  for (let k = 3; k < px.length; k += 4) if (px[k] !== 0) return true;
  return false;
}
