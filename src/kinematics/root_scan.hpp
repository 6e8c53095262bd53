#pragma once
// All roots of a scalar function on an interval, by sampling for sign changes and bisecting each bracket: the
// 1-D searches of the assembly-mode enumerations (the 6-3 hexapod's restructuring, the tripod's joint-angle
// scan). `f(t)` returns std::optional<double>: empty where the function is undefined (a branch that does not
// exist there); a bracket needs the function defined at both ends. Two roots closer than one sample step can
// be missed. `on_root(t)` is called right after f(t), so whatever state f fills in (the joint positions) is
// the root's.
#include <optional>

namespace pkm {

template <class Function, class OnRoot>
void scan_roots(Function&& f, double from, double to, int samples, OnRoot&& on_root) {
  constexpr int kBisections = 80;  // halves a bracket of ~2π/3000 far below double precision
  std::optional<double> previous;
  double previous_t = from;
  for (int s = 0; s <= samples; ++s) {
    const double t = from + (to - from) * s / samples;
    const std::optional<double> value = f(t);
    if (value && previous && (*value == 0.0 || (*value > 0) != (*previous > 0))) {
      double lo = previous_t, hi = t, f_lo = *previous;
      bool defined = true;
      for (int i = 0; i < kBisections && defined; ++i) {
        const double mid = 0.5 * (lo + hi);
        const std::optional<double> f_mid = f(mid);
        defined = f_mid.has_value();
        if (!defined) break;
        if ((*f_mid > 0) == (f_lo > 0)) {
          lo = mid;
          f_lo = *f_mid;
        } else {
          hi = mid;
        }
      }
      if (f(0.5 * (lo + hi))) on_root(0.5 * (lo + hi));
    }
    previous = value;
    previous_t = t;
  }
}

}  // namespace pkm
