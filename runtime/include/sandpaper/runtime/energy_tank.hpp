#pragma once
// Bounds the energy that non-passive force terms put into the hand: an energy tank in the sense of
// Franken, Stramigioli, Misra, Secchi and Macchelli, "Bilateral telemanipulation with time delays: a
// two-layer approach combining passivity and transparency", IEEE Trans. Robotics 27(4), 2011.
// docs/RUNTIME.md, "Energy bound", states the rule and the bound it gives. Allocation-free.

namespace sandpaper::runtime {

class EnergyTank {
 public:
  // `budget_J` (J, >= 0): what the tank holds when full; `refill_W` (W, >= 0): what it gains per
  // second. Starts full. Budget 0 with refill 0 silences the terms it guards.
  EnergyTank(double budget_J, double refill_W) noexcept : budget_J_(budget_J), refill_W_(refill_W), level_J_(budget_J) {}

  void fill() noexcept { level_J_ = budget_J_; }

  // One tick: the guarded force delivers `power_W` (W, force . hand velocity) over `dt_s` (s).
  // Returns the factor (0 to 1) to scale that force by so the tank can pay for it: it gains
  // refill * dt and whatever the force absorbs (power < 0), pays power * dt when power > 0, scales
  // the force down to what it holds when it cannot pay in full, and keeps at most the budget for the
  // next tick. A non-finite power gives a NaN factor so that the fault reaches the servo loop.
  double pass_rt(double power_W, double dt_s) noexcept;

  double level_J() const noexcept { return level_J_; }
  double budget_J() const noexcept { return budget_J_; }
  double refill_W() const noexcept { return refill_W_; }

 private:
  double budget_J_;
  double refill_W_;
  double level_J_;
};

}  // namespace sandpaper::runtime
