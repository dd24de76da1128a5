#pragma once
// Changes the material under the hand while the servo loop plays, without locks or allocation on
// the servo thread (docs/RUNTIME.md, "Hot swap"). The application thread builds the new force
// source (a PatchEvaluator of a freshly compiled program, a WorkspaceEvaluator) and offers it; the
// servo thread picks it up at its next tick, resets it under the hand, and blends the force from
// the old source to the new one; the old one goes back to the application thread to be freed.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>

#include "sandpaper/runtime/force_source.hpp"
#include "sandpaper/runtime/spsc_ring.hpp"

namespace sandpaper::runtime {

class SwappableSource final : public ForceSource {
 public:
  static constexpr double kDefaultCrossfade_s = 0.005;

  // Plays `initial` (may be null: zero force until a source is offered). `crossfade_s` (s, >= 0,
  // finite; 0 switches at once): after a swap the force is (1 - a) F_old + a F_new with a rising
  // linearly from 0 to 1 over this time, so the new material's force ramps up from zero while the
  // old one fades out. Throws std::invalid_argument for a negative or non-finite crossfade.
  explicit SwappableSource(std::unique_ptr<ForceSource> initial, double crossfade_s = kDefaultCrossfade_s);
  // Frees every source it holds. Only once the servo loop playing it has stopped.
  ~SwappableSource() override;
  SwappableSource(const SwappableSource&) = delete;
  SwappableSource& operator=(const SwappableSource&) = delete;

  // Application thread (one at a time). Hands `next` to the servo thread with one atomic exchange;
  // a source offered earlier and not yet picked up is replaced, and freed here (it never played).
  // Never blocks. The source must be built (allocated) already, and anything it refers to (its
  // PatchProgram) must live until collect_retired_nonrt() has freed it.
  void offer_nonrt(std::unique_ptr<ForceSource> next);
  // Application thread. Frees the sources the servo thread has finished with; returns how many.
  // Call it now and then (e.g. after each offer, or once a second).
  std::size_t collect_retired_nonrt();
  // True while an offered source has not been picked up yet, or a crossfade is under way.
  bool swap_pending_nonrt() const noexcept;
  // Offered sources the servo thread has picked up (and started blending in) since construction.
  std::uint64_t swaps_picked_up() const noexcept { return swaps_picked_up_.load(std::memory_order_acquire); }

  // Servo thread. Picks up an offered source (reset_rt(hand) first), blends, retires the old one.
  glm::dvec2 force_rt(const HandState& hand, double dt_s) noexcept override;
  // Servo thread. Resets the current source; any blend in progress ends on the current source.
  void reset_rt(const HandState& hand) noexcept override;

 private:
  void finish_fade_rt() noexcept;

  double crossfade_s_;
  std::atomic<ForceSource*> offered_{nullptr};  // application -> servo, single slot
  SpscRing<ForceSource*> retired_;              // servo -> application
  // Servo thread's own; read by the destructor only after the loop has stopped.
  ForceSource* current_ = nullptr;
  ForceSource* fading_out_ = nullptr;  // the previous source while the blend runs or until retired
  double fade_elapsed_s_ = 0;
  bool fading_ = false;
  std::atomic<bool> busy_{false};  // fading or holding an unretired source: for swap_pending_nonrt
  std::atomic<std::uint64_t> swaps_picked_up_{0};
};

}  // namespace sandpaper::runtime
