// What the joint kinds share on the core side: the checks of a definition's two ends, the
// spring lanes, and the explicit instantiation of a kind's lane functions for every width.
#pragma once

#include <string>

#include "softstep/simd/joint_lanes.hpp"
#include "validation.hpp"
#include "world_impl.hpp"

namespace softstep {

// Whether a joint kind solves point rows (a 2- or 3-row block at its anchors), whose float
// effective mass bounds how far a dynamic body's anchor may lie (validation::point_lever).
enum class PointRows { Yes, No };

// A slot with the checked ends of a definition named `def` ("RevoluteJointDef"): live and
// distinct bodies, finite anchors, not both unable to move, and for point rows anchors within
// validation::point_lever of a dynamic body's centre. Throws InvalidArgument.
// The anchors are named `<def>.<anchor_a>` and `<def>.<anchor_b>`, as the Def spells them.
JointSlot checked_joint_ends(const World::Impl& w, std::string_view call, std::string_view def,
                             BodyId a, BodyId b, const Eigen::Vector3d& local_anchor_a,
                             const Eigen::Vector3d& local_anchor_b, PointRows point_rows,
                             std::string_view anchor_a = "local_anchor_a",
                             std::string_view anchor_b = "local_anchor_b");

// validation::point_lever for every joint with point rows on body `slot`, as if its mass
// properties were these (set_mass_properties).
void check_point_levers(const World::Impl& w, std::string_view call, std::string_view field,
                        std::uint32_t slot, double mass, const Eigen::Matrix3d& inertia);

template <int W>
void fill_spring_lanes(simd::SoftRowLanes<W>& g, int lane, const Spring& spring) {
  g.hertz[lane] = static_cast<float>(spring.hertz);
  g.zeta[lane] = static_cast<float>(spring.damping_ratio);
}

// World-frame anchor positions now, from the double poses.
struct WorldAnchors {
  Eigen::Vector3d a, b;
};
WorldAnchors world_anchors(const World::Impl& w, const JointSlot& j);

class StateHasher;

// A spring into the state hash: a relative one as it always was (the golden hashes hold), an
// absolute one with its units, k and c after.
void hash_spring(StateHasher& h, const Spring& spring);

// The effective mass m_eff = 1/K a row sees now, from the double poses (JointReading's
// effective_mass): a linear row pushing B along unit n at arm_b from its centre and A back at
// arm_a, K = 1/m_a + 1/m_b + (arm_a x n).I_a^-1 (arm_a x n) + (arm_b x n).I_b^-1 (arm_b x n),
// kg; an angular row about unit n, K = n.(I_a^-1 + I_b^-1) n, kg m^2. Only dynamic bodies
// count; +infinity when neither end can move along the row.
double linear_effective_mass(const BodySlot& a, const BodySlot& b, const Eigen::Vector3d& arm_a,
                             const Eigen::Vector3d& arm_b, const Eigen::Vector3d& n);
double angular_effective_mass(const BodySlot& a, const BodySlot& b, const Eigen::Vector3d& n);

// The lane functions of kind K for the four widths, in the kind's .cpp.
#define SOFTSTEP_INSTANTIATE_KIND_LANES(K, W)                         \
  template void K::fill_lane<W>(K::Group<W>&, int, const JointSlot&); \
  template void K::read_impulses<W>(const K::Group<W>&, int, float*); \
  template void K::clear_impulses<W>(K::Group<W>&);
// write_step_start, for the kinds that define it in their .cpp.
#define SOFTSTEP_INSTANTIATE_STEP_START(K)                                               \
  template void K::write_step_start<1>(K::Group<1>&, int, JointSlot&, const BodySlots&); \
  template void K::write_step_start<4>(K::Group<4>&, int, JointSlot&, const BodySlots&); \
  template void K::write_step_start<8>(K::Group<8>&, int, JointSlot&, const BodySlots&); \
  template void K::write_step_start<16>(K::Group<16>&, int, JointSlot&, const BodySlots&);
#define SOFTSTEP_INSTANTIATE_KIND(K)    \
  SOFTSTEP_INSTANTIATE_KIND_LANES(K, 1) \
  SOFTSTEP_INSTANTIATE_KIND_LANES(K, 4) \
  SOFTSTEP_INSTANTIATE_KIND_LANES(K, 8) \
  SOFTSTEP_INSTANTIATE_KIND_LANES(K, 16)

}  // namespace softstep
