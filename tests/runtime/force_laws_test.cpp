// Every term kind's force, tick by tick along recorded hand paths, against the law written out here
// again from the thesis' form (Appendix B; 3.2.2; 3.4), not by calling the kernels. Non-passive terms
// get an energy budget too large to matter: the tank has its own tests (energy_bound_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "runtime_test_support.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "term_samples.hpp"

namespace sandpaper::runtime {
namespace {

using namespace testing;
constexpr double kPi = std::numbers::pi;

// A recorded hand: positions from a SimJoystick script at the servo rate, velocity and acceleration
// by central differences of the script (any values would do: the laws only need them to be known).
std::vector<HandState> record(const HandScript& script, double rate_hz, double duration_s) {
  const SimJoystick joystick(sim_device_limits(), script, 0);
  const double d = 1e-4;
  std::vector<HandState> hands;
  for (int k = 0; k < static_cast<int>(duration_s * rate_hz); ++k) {
    const double t = k / rate_hz;
    HandState h;
    h.position_m = joystick.hand_position(t);
    const glm::dvec2 before = joystick.hand_position(t - d), after = joystick.hand_position(t + d);
    h.velocity_m_s = (after - before) / (2 * d);
    h.acceleration_m_s2 = (after - 2.0 * h.position_m + before) / (d * d);
    hands.push_back(h);
  }
  return hands;
}

// A circle through all four quadrants and a diagonal scan through the centre to near the corners.
std::vector<std::vector<HandState>> recorded_paths() {
  return {record(HandScript{HandPath::Circle, 0.1, 0.035, 0.0}, 1000, 3.0),
          record(HandScript{HandPath::Scan, 0.07, 0.045, 0.7}, 1000, 3.0)};
}

schema::PatchProgram unbounded(std::vector<schema::Term> terms) {
  auto program = program_of(std::move(terms));
  program.energy_budget_J = 1e12;
  return program;
}

using Law = std::function<glm::dvec2(const HandState&)>;

// Plays `term` alone along each recorded path (reset at the first sample, dt = 0 on the first tick
// as the servo loop does) and compares every tick with `law`.
void expect_law(const schema::Term& term, const Law& law, double tolerance_N = 1e-9) {
  const auto program = unbounded({term});
  for (const auto& path : recorded_paths()) {
    PatchEvaluator evaluator(program);
    evaluator.reset_rt(path.front());
    double largest = 0;
    for (std::size_t k = 0; k < path.size(); ++k) {
      const glm::dvec2 got = evaluator.force_rt(path[k], k == 0 ? 0.0 : 1e-3);
      const glm::dvec2 want = law(path[k]);
      largest = std::max(largest, std::hypot(want.x, want.y));
      ASSERT_NEAR(got.x, want.x, tolerance_N) << "tick " << k;
      ASSERT_NEAR(got.y, want.y, tolerance_N) << "tick " << k;
    }
    EXPECT_GT(largest, 0.05) << "the path should make the law push noticeably";
  }
}

TEST(ForceLaws, Spring) {
  expect_law(spring(150, 0.004, -0.003), [](const HandState& h) {
    return glm::dvec2{-150 * (h.position_m.x - 0.004), -150 * (h.position_m.y + 0.003)};
  });
}

TEST(ForceLaws, ViscousAndAntiViscous) {
  for (double b : {4.0, -4.0})
    expect_law(damper(b), [b](const HandState& h) { return -b * h.velocity_m_s; });
}

// A triangle wave sampled with a sample on each kink: linear interpolation reproduces it exactly.
TEST(ForceLaws, GratingInterpolatesItsTableAlongTheNormal) {
  schema::GratingTerm g;
  g.period_m = 0.0045;
  g.orientation_rad = 2.2;
  const auto tri = [](double u) { return 1.5 * (1 - 4 * std::abs(u - std::floor(u) - 0.5)); };
  for (int i = 0; i < 64; ++i) g.force_N.push_back(static_cast<float>(tri(i / 64.0)));
  expect_law(g, [&](const HandState& h) {
    const double nx = std::cos(2.2), ny = std::sin(2.2);
    const double f = tri((h.position_m.x * nx + h.position_m.y * ny) / 0.0045);
    return glm::dvec2{f * nx, f * ny};
  }, 1e-7);
}

// A bilinear function sampled on the grid is reproduced exactly by bilinear interpolation (up to the
// tables' float storage).
TEST(ForceLaws, HeightFieldInterpolatesItsGrid) {
  const auto fx = [](double x, double y) { return 0.3 + 20 * x - 15 * y + 900 * x * y; };
  const auto fy = [](double x, double y) { return -0.2 - 10 * x + 25 * y - 600 * x * y; };
  schema::HeightFieldTerm field;
  field.nx = field.ny = 21;
  field.origin_m[0] = field.origin_m[1] = -0.05;
  field.spacing_m[0] = field.spacing_m[1] = 0.005;
  for (std::uint32_t iy = 0; iy < 21; ++iy)
    for (std::uint32_t ix = 0; ix < 21; ++ix) {
      field.force_x_N.push_back(static_cast<float>(fx(-0.05 + 0.005 * ix, -0.05 + 0.005 * iy)));
      field.force_y_N.push_back(static_cast<float>(fy(-0.05 + 0.005 * ix, -0.05 + 0.005 * iy)));
    }
  expect_law(field, [&](const HandState& h) {
    return glm::dvec2{fx(h.position_m.x, h.position_m.y), fy(h.position_m.x, h.position_m.y)};
  }, 1e-6);
}

TEST(ForceLaws, Const) {
  expect_law(constant_force(0.4, -0.7), [](const HandState&) { return glm::dvec2{0.4, -0.7}; });
}

// Appendix B: Fx = -b vx, Fy = abs(-b vy).
TEST(ForceLaws, Nap) {
  expect_law(nap(3), [](const HandState& h) {
    return glm::dvec2{-3 * h.velocity_m_s.x, std::abs(-3 * h.velocity_m_s.y)};
  });
}

// Appendix B Wave: F = -A sin(2 pi p / P) on each axis.
TEST(ForceLaws, WaveOnEachAxis) {
  for (const auto& [on_x, on_y] : {std::pair{true, true}, std::pair{true, false}, std::pair{false, true}}) {
    expect_law(periodic(schema::PeriodicShape::Sine, 0.9, 0.007, on_x, on_y), [&](const HandState& h) {
      return glm::dvec2{on_x ? -0.9 * std::sin(2 * kPi * h.position_m.x / 0.007) : 0.0,
                        on_y ? -0.9 * std::sin(2 * kPi * h.position_m.y / 0.007) : 0.0};
    });
  }
}

// Appendix B Cusp, "[abs(p / f) mod (2 A)] - A", with f = P / (2 A) so that the force climbs from -A
// to A over each period P of |p|.
TEST(ForceLaws, CuspIsASawtoothOfTheDistanceFromTheAxis) {
  const double A = 0.6, P = 0.005, f = P / (2 * A);
  expect_law(periodic(schema::PeriodicShape::Sawtooth, A, P), [&](const HandState& h) {
    return glm::dvec2{std::fmod(std::abs(h.position_m.x / f), 2 * A) - A,
                      std::fmod(std::abs(h.position_m.y / f), 2 * A) - A};
  }, 1e-8);
}

// Thesis 3.4: the force points to the centre of the wave the hand is in, (n + 1/2) P, growing
// linearly from 0 there to A at the wave's edges.
TEST(ForceLaws, TriangleWavePullsTowardEachWaveCentre) {
  const double A = 0.7, P = 0.006;
  const auto axis = [&](double u) {
    const double centre = (std::floor(u / P) + 0.5) * P;
    return -A * (u - centre) / (P / 2);
  };
  expect_law(periodic(schema::PeriodicShape::Triangle, A, P), [&](const HandState& h) {
    return glm::dvec2{axis(h.position_m.x), axis(h.position_m.y)};
  }, 1e-8);
}

// Appendix B Ridge: Fx = k ([px mod wavelength] - ridge width), Fy = 0; the modulo taken into
// [0, wavelength) on both sides of the centre.
TEST(ForceLaws, Ridge) {
  expect_law(ridge(300, 0.006, 0.002), [](const HandState& h) {
    double m = std::fmod(h.position_m.x, 0.006);
    if (m < 0) m += 0.006;
    return glm::dvec2{300 * (m - 0.002), 0.0};
  }, 1e-8);
}

// Bowl: toward the centre, |F| = k |p|^1.5 / sqrt(r).
TEST(ForceLaws, BowlStiffensWithDistance) {
  expect_law(bowl(150, 0.03), [](const HandState& h) {
    const double r = std::hypot(h.position_m.x, h.position_m.y);
    if (r == 0) return glm::dvec2{0, 0};
    const double magnitude = 150 * std::pow(r, 1.5) / std::sqrt(0.03);
    return -magnitude * h.position_m / r;
  });
}

// Appendix B Buckle: Fx = v1 px - v2 py, Fy = v1 py + v2 px; Circle is v1 = 0, Bump is v2 = 0.
TEST(ForceLaws, BuckleCircleAndBump) {
  for (const auto& [v1, v2] : {std::pair{-50.0, 40.0}, std::pair{0.0, 60.0}, std::pair{80.0, 0.0}}) {
    expect_law(linear_field(v1, v2), [&](const HandState& h) {
      const double x = h.position_m.x, y = h.position_m.y;
      return glm::dvec2{v1 * x - v2 * y, v1 * y + v2 * x};
    });
  }
}

// Thesis 3.2.2: a spring acting only along one direction, toward a line through the centre.
TEST(ForceLaws, LinearSpring) {
  expect_law(linear_spring(200, 0.7, 0.001, -0.002), [](const HandState& h) {
    const double nx = std::cos(0.7), ny = std::sin(0.7);
    const double distance = (h.position_m.x - 0.001) * nx + (h.position_m.y + 0.002) * ny;
    return glm::dvec2{-200 * distance * nx, -200 * distance * ny};
  });
}

// Appendix B Minus, as the OCR's x component reads: F = k (J - M), M the joystick's predicted position
// `lead` ahead, so it holds the hand back from where it is going.
TEST(ForceLaws, MinusPushesAwayFromThePredictedPosition) {
  expect_law(minus(100, 0.03), [](const HandState& h) {
    const glm::dvec2 predicted = h.position_m + 0.03 * h.velocity_m_s + 0.5 * 0.03 * 0.03 * h.acceleration_m_s2;
    return 100.0 * (h.position_m - predicted);
  });
}

// ATNSpring, as the OCR's x component reads: F = k (p - m), dm/dt = (p - m) / lag. For a hand moving at constant velocity v from
// rest on m: continuously, p - m = v lag (1 - exp(-t / lag)); with the hand sampled every dt and held,
// p_k - m_k = v dt e (1 - e^k) / (1 - e), e = exp(-dt / lag).
TEST(ForceLaws, FollowerSpringLagsAsTheClosedForm) {
  const double k = 150, lag = 0.05, dt = 1e-3;
  const glm::dvec2 start{-0.03, 0.01}, v{0.04, -0.015};
  auto program = program_of({follower_spring(k, lag)});
  program.energy_budget_J = 1e9;  // active since issue 15 (F = k (p - m)): a budget the run never empties
  PatchEvaluator evaluator(program);
  HandState hand;
  hand.position_m = start;
  hand.velocity_m_s = v;
  evaluator.reset_rt(hand);
  const double e = std::exp(-dt / lag);
  for (int i = 0; i <= 1500; ++i) {
    hand.position_m = start + (i * dt) * v;
    const glm::dvec2 f = evaluator.force_rt(hand, i == 0 ? 0.0 : dt);
    const glm::dvec2 sampled = k * (v * dt * e * (1 - std::pow(e, i)) / (1 - e));
    const glm::dvec2 continuous = k * (v * lag * (1 - std::exp(-i * dt / lag)));
    ASSERT_NEAR(f.x, sampled.x, 1e-10) << i;
    ASSERT_NEAR(f.y, sampled.y, 1e-10) << i;
    // The sampled hand differs from the continuous one by at most one tick of travel.
    ASSERT_NEAR(f.x, continuous.x, k * std::abs(v.x) * dt) << i;
    ASSERT_NEAR(f.y, continuous.y, k * std::abs(v.y) * dt) << i;
  }
  // Caught up: the steady lag is v lag.
  const glm::dvec2 m = evaluator.state_of(0)->follower_m;
  EXPECT_NEAR(glm::length(hand.position_m - m), glm::length(v) * lag, glm::length(v) * dt);
}

// Attractor: F = -k (p - q(t)), q on the swirling path, t the time since reset; several periods so
// that the wrapped clock is exercised.
TEST(ForceLaws, AttractorFollowsItsPathInTime) {
  const double k = 80, R = 0.02, T = 1.5, s = 0.3, cx = 0.001, cy = -0.002;
  const auto q = [&](double t) {
    const double theta = 2 * kPi * t / T;
    const double r = R * (1 + s * std::sin(3 * theta)) / (1 + s);
    return glm::dvec2{cx + r * std::cos(theta), cy + r * std::sin(theta)};
  };
  const auto program = unbounded({attractor(k, R, T, s, cx, cy)});
  const auto path = record(HandScript{HandPath::Circle, 0.05, 0.03, 0.0}, 1000, 10.0);
  PatchEvaluator evaluator(program);
  evaluator.reset_rt(path.front());
  for (std::size_t i = 0; i < path.size(); ++i) {
    const glm::dvec2 f = evaluator.force_rt(path[i], i == 0 ? 0.0 : 1e-3);
    const glm::dvec2 want = -k * (path[i].position_m - q(static_cast<double>(i) * 1e-3));
    ASSERT_NEAR(f.x, want.x, 1e-9) << i;
    ASSERT_NEAR(f.y, want.y, 1e-9) << i;
  }
}

TEST(ForceLaws, FirstTickAdvancesNoState) {
  const auto program = unbounded({follower_spring(100, 0.02), one_mass(0.1, 200, 0.5), attractor(50, 0.02, 1.0, 0.0)});
  PatchEvaluator evaluator(program);
  HandState hand;
  hand.position_m = {0.01, 0.02};
  hand.velocity_m_s = {0.3, 0.1};
  evaluator.reset_rt(hand);
  const TermState follower = *evaluator.state_of(0), masses = *evaluator.state_of(1), clock = *evaluator.state_of(2);
  hand.position_m = {0.02, -0.01};
  const glm::dvec2 f = evaluator.force_rt(hand, 0.0);
  EXPECT_TRUE(std::isfinite(f.x) && std::isfinite(f.y));
  EXPECT_EQ(evaluator.state_of(0)->follower_m, follower.follower_m);
  EXPECT_EQ(evaluator.state_of(1)->masses.position_m[0], masses.masses.position_m[0]);
  EXPECT_EQ(evaluator.state_of(1)->masses.velocity_m_s[0], masses.masses.velocity_m_s[0]);
  EXPECT_EQ(evaluator.state_of(2)->time_s, clock.time_s);
  EXPECT_EQ(evaluator.state_of(3), nullptr);
}

// Every stateless kind at once is the sum of each alone, in order.
TEST(ForceLaws, TermsAreSummed) {
  const std::vector<schema::Term> terms = {spring(120, 0.002), damper(-1.5), constant_force(0.3, -0.2), nap(2.0),
                                           periodic(schema::PeriodicShape::Sine, 0.8, 0.004), ridge(300, 0.006, 0.002),
                                           bowl(150, 0.03), linear_field(-50, 40), linear_spring(200, 0.7, 0.001, 0),
                                           minus(100, 0.02)};
  const auto together = unbounded(terms);
  std::vector<schema::PatchProgram> alone;
  for (const auto& term : terms) alone.push_back(unbounded({term}));
  for (const auto& path : recorded_paths()) {
    PatchEvaluator sum(together);
    std::vector<PatchEvaluator> parts(alone.begin(), alone.end());
    for (std::size_t k = 0; k < path.size(); k += 7) {
      glm::dvec2 want{0, 0};
      for (auto& part : parts) want += part.force_rt(path[k], 1e-3);
      const glm::dvec2 got = sum.force_rt(path[k], 1e-3);
      ASSERT_NEAR(got.x, want.x, 1e-12);
      ASSERT_NEAR(got.y, want.y, 1e-12);
    }
  }
}

}  // namespace
}  // namespace sandpaper::runtime
