// Contact force store: what the contact law (systems/contact_law.h) gives each contact element
// at the last evaluation, for fibre-fibre and fibre-tool elements alike (one instance each, in
// the order of their element store). No logic here.
#pragma once

#include "components/particle_weights.h"
#include "core/types.h"

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace fibra {

// A contact element's section as weights on the nodal centres x0 of its fibre: x0(s) =
// sum_i centre[i] x0_node[i], dx0/ds(s) = sum_i tangent[i] x0_node[i] (systems/geometry's
// contactSection: at an interior node the tangent is the mean of two elements', 5 nodes at most).
struct SectionWeights {
  int count = 0;                     // 0: the element is not linearised in its normal
  std::array<Index, 5> node{};       // global nodes
  std::array<double, 5> centre{};    // -
  std::array<double, 5> tangent{};   // 1/mm
};

// The derivatives of an element's forces on I with respect to everything its normal, gap and
// slip read (systems/normal_linearisation.h): v = (x_N^I, x_N^J, x0I, x0J, dx0/ds|I, dx0/ds|J,
// x^I, x^J), x_N the points the normal force acts on (the facing particles, else the material
// ones), x the material particles (the friction force's).
struct NormalJacobian {
  using Block = Eigen::Matrix<double, 3, 24>;
  Block dfN = Block::Zero();  // d(R_N N)/dv, N/mm, N
  Block dfT = Block::Zero();  // d f_T/dv (friction), N/mm, N
  // rows 2s, 2s + 1: d xi/dv of side s's facing point (xi its coordinates on the directors, mm)
  // through N alone (the directors' part is the rolling stiffness); zero without facing points
  Eigen::Matrix<double, 4, 24> dxi = Eigen::Matrix<double, 4, 24>::Zero();  // mm/mm, mm
  SectionWeights I, J;
};

struct ContactForceStore {
  // --- per contact element ---
  std::vector<double> gap;          // g_N = (x^I - x^J) . N, mm (negative: penetration)
  std::vector<double> normalForce;  // R_N >= 0, N
  std::vector<Vec3> normal;         // N the force was computed with (unit; the element's own may
                                    // have turned since, in loop B), -
  std::vector<Vec3> force;          // f on particle I (J or the tool gets -f), N
  std::vector<Eigen::Matrix3d> stiffness;  // S = -df/d(x^I - x^J), N/mm
  std::vector<Vec3> gRev;           // reversible slip, mm
  std::vector<std::uint8_t> slip;   // 1 when the trial slip left the disc of radius g_T,max
  // with the normal linearised (contact.normal_update "newton", fibre-fibre elements; else
  // empty): the forces' derivatives and the sections' weights (with contact.facing_particles its
  // normal force acts on the facing particles below, facing 1); an element with I.count == 0
  // uses `stiffness`
  std::vector<NormalJacobian> normalJacobian;
  // With contact.facing_particles (else empty), fibre-fibre elements (systems/facing_particles.h): the particles the normal force acted on, the points of the two
  // outlines extremal along N at this evaluation (facing 1; 0: the element's material
  // particles), and the outlines' rolling stiffness as weights c = sqrt(R / rho) N_a v on the
  // directors (sqrt(mm), per side), with K += R_N (c (x) N)(c (x) N)^T. On a facing element
  // `stiffness` is the normal force's -d(R_N N)/d(x^I - x^J) on the facing particles, and the
  // friction force f - R_N N acts on the material particles with the two blocks below
  // (systems/contact_law.h contactLawSplit; zero where frictionless).
  std::vector<std::uint8_t> facing;
  std::vector<ParticleWeights> facingI, facingJ;
  std::vector<ParticleWeights> rollingI, rollingJ;
  std::vector<Eigen::Matrix3d> frictionStiffness;  // -df_T/dd on the material particles, N/mm
  std::vector<Eigen::Matrix3d> coupling;           // -df_T/dd on the facing particles, N/mm

  Index size() const { return Index(gap.size()); }
};

}  // namespace fibra
