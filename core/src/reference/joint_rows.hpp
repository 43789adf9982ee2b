// The rows of one joint at a given pose, in double precision: the one place the references
// and the energy metric turn a joint definition into J, C and K = J M^-1 J^T.
#pragma once

#include <Eigen/Core>
#include <stdexcept>
#include <string>

#include "softstep/world.hpp"

namespace softstep::reference {

// A body as the rows need it.
struct BodyFrame {
  Eigen::Vector3d position;
  Quaternion orientation;
  double inverse_mass;
  Eigen::Matrix3d inverse_inertia;  // world frame
};

struct JointRows {
  std::uint32_t body_a = 0, body_b = 0;  // body slots
  int count = 0;                         // rows: 3 ball, 1 distance, 0 a free spring
  // Row r, columns [v_a w_a v_b w_b]: C_dot = J v.
  Eigen::Matrix<double, 3, 12> jacobian = Eigen::Matrix<double, 3, 12>::Zero();
  Eigen::Vector3d error = Eigen::Vector3d::Zero();  // C per row, m
  Eigen::Matrix3d k = Eigen::Matrix3d::Zero();      // J M^-1 J^T, 1/kg (count x count)
  Spring spring;
  bool has_limits = false;  // a distance joint with a min or max limit row
};

// The frame of a body slot from the caller (capture or current state).
template <class FrameOf>
JointRows joint_rows(const World& world, JointId joint, FrameOf&& frame_of);

JointRows joint_rows_between(const BodyFrame& a, const BodyFrame& b,
                             const Eigen::Vector3d& local_anchor_a,
                             const Eigen::Vector3d& local_anchor_b, bool ball, double rest_length);

// Ball and distance joints only, so far: the angular types' rows are not exported to the
// references yet (the exact reference and the energy metric throw std::invalid_argument).
template <class FrameOf>
JointRows joint_rows(const World& world, JointId joint, FrameOf&& frame_of) {
  JointRows rows;
  const JointType type = world.joint_type(joint);
  if (type != JointType::Ball && type != JointType::Distance) {
    throw std::invalid_argument(std::string("the exact references model ball and distance "
                                            "joints only; joint ") +
                                std::to_string(joint.index) + " is a " + joint_type_name(type) +
                                " joint");
  }
  if (type == JointType::Ball) {
    const BallJointDef d = world.ball_joint(joint);
    rows = joint_rows_between(frame_of(d.body_a), frame_of(d.body_b), d.local_anchor_a,
                              d.local_anchor_b, true, 0.0);
    rows.body_a = d.body_a.index;
    rows.body_b = d.body_b.index;
    rows.spring = d.spring;
  } else {
    const DistanceJointDef d = world.distance_joint(joint);
    rows = joint_rows_between(frame_of(d.body_a), frame_of(d.body_b), d.local_anchor_a,
                              d.local_anchor_b, false, d.rest_length);
    rows.body_a = d.body_a.index;
    rows.body_b = d.body_b.index;
    rows.spring = d.spring;
    rows.has_limits =
        !d.spring.is_rigid() &&
        (d.min_length > 0.0 || d.max_length != std::numeric_limits<double>::infinity());
    if (d.spring.is_free()) rows.count = 0;
  }
  return rows;
}

}  // namespace softstep::reference
