#include "sandpaper/runtime/swappable_source.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sandpaper::runtime {
namespace {

// The servo thread retires at most one source per swap and picks up no new one while a retired
// source is still waiting for room, so a few slots are plenty; a full ring only delays the next swap.
constexpr std::size_t kRetiredSlots = 8;

}  // namespace

SwappableSource::SwappableSource(std::unique_ptr<ForceSource> initial, double crossfade_s)
    : crossfade_s_(crossfade_s), retired_(kRetiredSlots), current_(initial.release()) {
  if (!std::isfinite(crossfade_s) || crossfade_s < 0) {
    delete current_;
    throw std::invalid_argument("swap crossfade time must be finite and >= 0 s");
  }
}

SwappableSource::~SwappableSource() {
  delete offered_.exchange(nullptr, std::memory_order_acq_rel);
  collect_retired_nonrt();
  delete fading_out_;
  delete current_;
}

void SwappableSource::offer_nonrt(std::unique_ptr<ForceSource> next) {
  // acq_rel: release publishes the new source's construction to the servo thread; acquire makes a
  // replaced, never-played source safe to delete here.
  ForceSource* unplayed = offered_.exchange(next.release(), std::memory_order_acq_rel);
  delete unplayed;
}

std::size_t SwappableSource::collect_retired_nonrt() {
  std::size_t freed = 0;
  ForceSource* old = nullptr;
  while (retired_.try_pop(old)) {
    delete old;
    ++freed;
  }
  return freed;
}

bool SwappableSource::swap_pending_nonrt() const noexcept {
  return offered_.load(std::memory_order_acquire) != nullptr || busy_.load(std::memory_order_acquire);
}

void SwappableSource::finish_fade_rt() noexcept {
  fading_ = false;
  if (fading_out_ != nullptr && retired_.try_push(fading_out_)) fading_out_ = nullptr;
  if (fading_out_ == nullptr) busy_.store(false, std::memory_order_release);
}

void SwappableSource::reset_rt(const HandState& hand) noexcept {
  if (fading_) finish_fade_rt();
  if (current_ != nullptr) current_->reset_rt(hand);
}

glm::dvec2 SwappableSource::force_rt(const HandState& hand, double dt_s) noexcept {
  // A source retired while the ring was full waits here; no new source is taken until it is gone,
  // so the servo thread never holds more than one old source.
  if (fading_out_ != nullptr && !fading_) finish_fade_rt();
  if (fading_out_ == nullptr && offered_.load(std::memory_order_relaxed) != nullptr) {
    // Busy before the slot empties, so swap_pending_nonrt() never sees a gap between the two.
    busy_.store(true, std::memory_order_release);
    // Only this thread empties the slot, so what was seen there is still there (or newer).
    ForceSource* next = offered_.exchange(nullptr, std::memory_order_acq_rel);
    if (next != nullptr) {
      next->reset_rt(hand);
      fading_out_ = current_;
      current_ = next;
      fade_elapsed_s_ = 0;
      fading_ = true;
      // At the tick of the swap a = 0: the force is still the old source's.
      swaps_picked_up_.fetch_add(1, std::memory_order_acq_rel);
    }
  }

  const glm::dvec2 now = current_ != nullptr ? current_->force_rt(hand, dt_s) : glm::dvec2{0, 0};
  if (!fading_) return now;
  // The old source keeps running (its state advancing) until it has faded out.
  const glm::dvec2 before = fading_out_ != nullptr ? fading_out_->force_rt(hand, dt_s) : glm::dvec2{0, 0};
  const double a = crossfade_s_ > 0 ? std::min(1.0, fade_elapsed_s_ / crossfade_s_) : 1.0;
  fade_elapsed_s_ += std::max(0.0, dt_s);
  if (a >= 1.0) {
    finish_fade_rt();
    return now;
  }
  return (1.0 - a) * before + a * now;
}

}  // namespace sandpaper::runtime
