// Built with no -march flags against the installed library (which may be built for AVX2):
// every public type that owns Eigen storage is created inside the library and destroyed
// here, so the two sides must agree on how that storage is allocated and freed (issue 17,
// bug 1: the reference API's Eigen vectors aborted with "double free or corruption").
#include <cstdio>
#include <softstep/reference.hpp>
#include <softstep/softstep.hpp>

int main() {
  softstep::World world;
  world.set_solve_capture(true);
  softstep::BodyDef ground;
  ground.type = softstep::BodyType::Static;
  softstep::BodyId previous = world.create_body(ground);
  for (int i = 1; i <= 5; ++i) {
    softstep::BodyDef link;
    link.position = {0.25 * i, 0.0, 0.0};
    const softstep::BodyId body = world.create_body(link);
    softstep::BallJointDef joint;
    joint.body_a = previous;
    joint.body_b = body;
    joint.local_anchor_a = {i == 1 ? 0.0 : 0.125, 0.0, 0.0};
    joint.local_anchor_b = {-0.125, 0.0, 0.0};
    world.create_ball_joint(joint);
    previous = body;
  }
  world.step(1.0 / 60.0);

  double residual = 0.0;
  int rows = 0;
  for (int round = 0; round < 3; ++round) {  // allocate and free more than once
    const softstep::reference::SoftSystem system = softstep::reference::first_substep_system(world);
    const softstep::reference::ExactSolution exact = softstep::reference::solve_exact(system);
    const Eigen::VectorXd r =
        softstep::reference::row_residual(system, exact.velocity, exact.impulse);
    softstep::reference::SoftSystem copy = system;   // copied and destroyed on this side
    copy.bias = Eigen::VectorXd::Zero(copy.rows());  // and reassigned from a consumer-built vector
    residual = r.cwiseAbs().maxCoeff();
    rows = system.rows();
    softstep::SolveCapture capture = world.solve_capture();  // a copy the consumer frees
    capture.velocity_before_solve.clear();
  }
  std::printf("reference: %d rows, exact residual %.3g m/s\n", rows, residual);
  return rows == 15 && residual < 1e-6 ? 0 : 1;
}
