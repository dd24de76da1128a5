// TextureTerms sums a program's gratings and height fields without the evaluator's per-tick work;
// what it gives must be the evaluator's force to the bit, or a surface in 3-D would feel a texture
// the 2-D patch does not.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/runtime/texture_terms.hpp"
#include "term_samples.hpp"

namespace sandpaper::runtime {
namespace {

namespace T = sandpaper::runtime::testing;

schema::PatchProgram texture_program() {
  schema::PatchProgram p;
  p.size_m[0] = p.size_m[1] = 1e9;  // as SurfaceTexture sets it: the texture goes on
  schema::GratingTerm oblique = T::sample_grating();
  oblique.orientation_rad = 0.52;  // neither axis, so both components of its normal count
  p.terms.emplace_back(oblique);
  schema::HeightFieldTerm repeating = T::sample_height_field();
  repeating.repeat = true;
  p.terms.emplace_back(repeating);
  p.terms.emplace_back(T::sample_height_field());  // not repeating: zero outside its grid
  return p;
}

TEST(TextureTerms, GivesTheEvaluatorsForceToTheBit) {
  const schema::PatchProgram p = texture_program();
  const TextureTerms terms(p);
  PatchEvaluator evaluator(p);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> x(-0.2, 0.2);
  int pushing = 0;
  for (int i = 0; i < 20000; ++i) {
    HandState hand;
    hand.position_m = {x(rng), x(rng)};
    const glm::dvec2 want = evaluator.force_rt(hand, 0.0);
    const glm::dvec2 got = terms.force_rt(hand.position_m);
    ASSERT_EQ(got.x, want.x) << i;
    ASSERT_EQ(got.y, want.y) << i;
    if (std::hypot(want.x, want.y) > 1e-3) ++pushing;
  }
  EXPECT_GT(pushing, 10000);  // the points were where the texture pushes, not on flat ground
  EXPECT_TRUE(std::isnan(terms.force_rt({NAN, 0.0}).x));
}

TEST(TextureTerms, RefusesAnythingButATexture) {
  schema::PatchProgram p = texture_program();
  p.terms.emplace_back(T::nap(0.5));
  EXPECT_THROW(TextureTerms{p}, std::invalid_argument);
  schema::PatchProgram bad;
  schema::GratingTerm g = T::sample_grating();
  g.force_N.resize(1);  // the evaluator's own check: a period needs two samples
  bad.terms.emplace_back(g);
  EXPECT_THROW(TextureTerms{bad}, std::invalid_argument);
}

}  // namespace
}  // namespace sandpaper::runtime
