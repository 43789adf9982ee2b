// Records a run for the viewer: a subsample of the bodies' positions and of the joints' error
// and force at up to max_frames moments, and every step's per-stage time, then writes them into
// one self-contained HTML page (viewer_page.html) that plays them back in 3D.
//
// Subsampling keeps the page fluent and small for 100,000-body worlds: the joints drawn are
// every k-th joint (with both of their bodies), plus every k-th body; frames are halved (every
// other one dropped, the interval doubled) whenever they exceed max_frames, so the length of a
// run need not be known in advance.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "softstep/world.hpp"

namespace softstep::tool {

struct ViewLimits {
  // The defaults give a 100,000-link chain scene a 7 MB page that draws a frame in 10-24 ms.
  std::size_t max_bodies = 2000;  // bodies drawn for their own sake (joint ends come on top)
  std::size_t max_joints = 3000;
  std::size_t max_frames = 150;
};

class ViewRecorder {
 public:
  // Picks what is drawn and records the world as it is (frame 0). The world must be profiling
  // (World::set_profiling) for the stage chart.
  ViewRecorder(const World& world, std::string title, const ViewLimits& limits = {});
  // After each step: its stage times, and a frame when one is due.
  void after_step(const World& world, double dt);
  // The page. Given the world, the last step is made a frame if it is not one.
  std::string page(const World* world = nullptr);

  std::size_t drawn_bodies() const { return bodies_.size(); }
  std::size_t drawn_joints() const { return joints_.size(); }
  std::size_t frames() const { return frame_steps_.size(); }

 private:
  void record_frame(const World& world);
  void decimate();

  std::string title_;
  ViewLimits limits_;
  std::size_t world_bodies_ = 0, world_joints_ = 0;
  Eigen::Vector3d gravity_;
  std::vector<BodyId> bodies_;
  std::string types_;  // per drawn body: 's'tatic, 'k'inematic, 'd'ynamic
  std::vector<JointId> joints_;
  std::vector<std::uint32_t> joint_ends_;  // per drawn joint: its two bodies' drawn indices
  std::vector<long> frame_steps_;
  std::vector<float> positions_;  // frames x bodies x 3, m
  std::vector<float> error_;      // frames x joints, m
  std::vector<float> force_;      // frames x joints, N
  std::vector<float> stage_ms_;   // steps x stages
  std::vector<float> step_ms_;    // steps
  std::vector<double> dt_;        // steps
  long steps_ = 0;
  long every_ = 1;  // steps between frames
};

// Bytes as base64 (the page carries its data inline).
std::string base64(const std::vector<std::uint8_t>& bytes);

}  // namespace softstep::tool
