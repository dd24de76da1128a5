#pragma once
// One valid example of every term kind, with parameters a material could have (forces of a few
// newtons over the patch), for the allocation test, the file round trips and the benchmarks' twin.
#include <cmath>
#include <cstdint>
#include <vector>

#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::runtime::testing {

inline schema::ConstantForceTerm constant_force(double fx, double fy) {
  schema::ConstantForceTerm t;
  t.force_N[0] = fx;
  t.force_N[1] = fy;
  return t;
}

inline schema::NapTerm nap(double b) {
  schema::NapTerm t;
  t.damping_Ns_per_m = b;
  return t;
}

inline schema::PeriodicTerm periodic(schema::PeriodicShape shape, double amplitude_N, double period_m, bool on_x = true,
                                     bool on_y = true) {
  schema::PeriodicTerm t;
  t.shape = shape;
  t.amplitude_N = amplitude_N;
  t.period_m = period_m;
  t.on_x = on_x;
  t.on_y = on_y;
  return t;
}

inline schema::RidgeTerm ridge(double k, double wavelength_m, double width_m) {
  schema::RidgeTerm t;
  t.stiffness_N_per_m = k;
  t.wavelength_m = wavelength_m;
  t.ridge_width_m = width_m;
  return t;
}

inline schema::BowlTerm bowl(double k, double radius_m) {
  schema::BowlTerm t;
  t.stiffness_N_per_m = k;
  t.radius_m = radius_m;
  return t;
}

inline schema::LinearFieldTerm linear_field(double radial, double tangential) {
  schema::LinearFieldTerm t;
  t.radial_N_per_m = radial;
  t.tangential_N_per_m = tangential;
  return t;
}

inline schema::LinearSpringTerm linear_spring(double k, double orientation_rad, double cx, double cy) {
  schema::LinearSpringTerm t;
  t.stiffness_N_per_m = k;
  t.orientation_rad = orientation_rad;
  t.centre_m[0] = cx;
  t.centre_m[1] = cy;
  return t;
}

inline schema::MinusTerm minus(double k, double lead_s) {
  schema::MinusTerm t;
  t.stiffness_N_per_m = k;
  t.lead_s = lead_s;
  return t;
}

inline schema::FollowerSpringTerm follower_spring(double k, double lag_s) {
  schema::FollowerSpringTerm t;
  t.stiffness_N_per_m = k;
  t.lag_s = lag_s;
  return t;
}

// The thesis' brick on a spring: one mass hanging under the hand.
inline schema::PointMassesTerm one_mass(double m_kg, double k, double c, double ground_c = 0, double gy = -9.81) {
  schema::PointMassesTerm t;
  t.count = 1;
  t.mass_kg[0] = m_kg;
  t.stiffness_N_per_m[0] = k;
  t.damping_Ns_per_m[0] = c;
  t.ground_damping_Ns_per_m = ground_c;
  t.gravity_m_s2[1] = gy;
  return t;
}

inline schema::PointMassesTerm two_masses(double m0, double m1, double k0, double k1, double c0, double c1,
                                          double ground_c = 0, double gx = 0, double gy = -9.81) {
  schema::PointMassesTerm t;
  t.count = 2;
  t.mass_kg[0] = m0;
  t.mass_kg[1] = m1;
  t.stiffness_N_per_m[0] = k0;
  t.stiffness_N_per_m[1] = k1;
  t.damping_Ns_per_m[0] = c0;
  t.damping_Ns_per_m[1] = c1;
  t.ground_damping_Ns_per_m = ground_c;
  t.gravity_m_s2[0] = gx;
  t.gravity_m_s2[1] = gy;
  return t;
}

inline schema::AttractorTerm attractor(double k, double radius_m, double period_s, double swirl, double cx = 0,
                                       double cy = 0) {
  schema::AttractorTerm t;
  t.stiffness_N_per_m = k;
  t.radius_m = radius_m;
  t.period_s = period_s;
  t.swirl = swirl;
  t.centre_m[0] = cx;
  t.centre_m[1] = cy;
  return t;
}

inline schema::FrictionTerm friction(double mu_static, double mu_kinetic, double press_N, double k = 2000,
                                     double stick_speed = 0.002) {
  schema::FrictionTerm t;
  t.static_coefficient = mu_static;
  t.kinetic_coefficient = mu_kinetic;
  t.press_N = press_N;
  t.stiffness_N_per_m = k;
  t.stick_speed_m_s = stick_speed;
  return t;
}

inline schema::NapFrictionTerm nap_friction(double mu_s, double mu_k, double against_s, double against_k, double press_N,
                                             double nap_rad = 1.5707963267948966, double k = 2000, double stick_speed = 0.002) {
  return {mu_s, mu_k, against_s, against_k, press_N, k, stick_speed, nap_rad};
}

// A small repeating height field with made-up gradients.
inline schema::HeightFieldTerm sample_height_field() {
  schema::HeightFieldTerm field;
  field.nx = field.ny = 16;
  field.origin_m[0] = field.origin_m[1] = -0.04;
  field.spacing_m[0] = field.spacing_m[1] = 0.005;
  field.repeat = true;
  for (std::uint32_t i = 0; i < field.nx * field.ny; ++i) {
    field.force_x_N.push_back(static_cast<float>(i % 7) * 0.1f - 0.3f);
    field.force_y_N.push_back(static_cast<float>(i % 5) * 0.1f - 0.2f);
  }
  return field;
}

inline schema::GratingTerm sample_grating() {
  schema::GratingTerm g;
  g.period_m = 0.003;
  g.orientation_rad = 0.4;
  for (int i = 0; i < 64; ++i) g.force_N.push_back(static_cast<float>(std::sin(i * 0.0981747704)));
  return g;
}

// One term of every kind, in the variant's order (index i holds alternative i).
inline std::vector<schema::Term> every_term_kind() {
  schema::SpringTerm spring;
  spring.stiffness_N_per_m = 120;
  spring.centre_m[0] = 0.002;
  schema::DamperTerm damper;
  damper.damping_Ns_per_m = 1.5;
  return {spring,
          damper,
          sample_grating(),
          sample_height_field(),
          constant_force(0.3, -0.2),
          nap(2.0),
          periodic(schema::PeriodicShape::Sawtooth, 0.8, 0.004, true, false),
          ridge(300, 0.006, 0.002),
          bowl(150, 0.03),
          linear_field(-50, 40),
          linear_spring(200, 0.7, 0.001, -0.002),
          minus(100, 0.02),
          follower_spring(150, 0.05),
          two_masses(0.05, 0.03, 200, 150, 0.5, 0.3, 0.1),
          attractor(80, 0.02, 1.5, 0.3, 0.001, 0.0),
          friction(0.9, 0.6, 1.5, 1800, 0.003),
          nap_friction(0.4, 0.3, 0.9, 0.7, 1.2, 1.4, 2200, 0.0025)};
}

}  // namespace sandpaper::runtime::testing
