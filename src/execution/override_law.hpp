#pragma once
// The time-scaling factor K of an executed motion: the executor plays the planned (nominal) motion q(τ) at
// τ̇ = K, so the drives move at q̇ = q'·K, q̈ = q''·K² + q'·K̇ and q⃛ = q'''·K³ + 3·q''·K·K̇ + q'·K̈. The
// operator's feed override sets K's target (1 = as planned), a feed hold or an abort sets it to 0; K follows
// with its rate |K̇| and its own acceleration |K̈| bounded, so that with the nominal motion planned inside the
// headroom of execution_headroom.hpp the drives stay within their speed, acceleration and jerk limits at
// every period, whenever the operator acts. (Smirnov 2019, §5.2.2, scales the ideal time by the override the
// same way, Δτ = K_V·h, eq. 161; its acceleration-limited ramp is the linear law here, with K̈ bounded in
// addition.)
//
// Per period K̈ is constant: K̇ and K change as its integrals, and the advance of τ over the period is the
// exact integral of K. K̇ aims at the braking curve sign(e)·sqrt(2·K̈_max·|e|) towards the target (e the
// distance to it), so K reaches the target without overshoot; it settles exactly on the target (so K = 1
// is exactly 1 and the executor can give the planned steps themselves).
namespace pkm::execution {

struct OverrideRates {
  double max_rate_per_s = 10.0;      ///< |K̇|: how fast the factor may change
  double max_accel_per_s2 = 1000.0;  ///< |K̈|
};

class OverrideLaw {
 public:
  OverrideLaw(const OverrideRates& rates, double period_s, double initial_factor = 1.0);
  /// One period towards `target` (≥ 0): returns the advance of τ over it, in periods (∫K dt / h).
  double advance(double target) noexcept;
  double factor() const noexcept { return factor_; }          ///< K at the end of the last period
  double rate_per_s() const noexcept { return rate_per_s_; }  ///< K̇ there
  /// At `target` and no longer changing.
  bool settled_at(double target) const noexcept { return factor_ == target && rate_per_s_ == 0.0; }
  void reset(double factor) noexcept;

 private:
  OverrideRates rates_;
  double period_s_;
  double factor_;
  double rate_per_s_ = 0.0;
};

}  // namespace pkm::execution
