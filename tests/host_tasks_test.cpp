// Threads on the host's terms (issue 17, hook 11): a step's workers run through the host's
// enqueue / finish callbacks with the same result as OpenMP and as one thread, and a forced
// thread count (WorldSettings::fixed_threads) is what every step uses. Named Threads.* so the
// ThreadSanitizer job runs them.
#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <thread>

#include "contacts/analytic_contacts.hpp"
#include "scenes/chain_scene.hpp"

namespace softstep {
namespace {

// The simplest host job system: a thread per task, joined by finish.
struct ThreadPerTask {
  std::atomic<int> enqueued{0};
  static void* enqueue(TaskCallbacks::Task task, int worker, void* task_context, void* self) {
    static_cast<ThreadPerTask*>(self)->enqueued.fetch_add(1, std::memory_order_relaxed);
    return new std::thread(task, worker, task_context);
  }
  static void finish(void* handle, void*) {
    auto* thread = static_cast<std::thread*>(handle);
    thread->join();
    delete thread;
  }
  TaskCallbacks callbacks() { return {&enqueue, &finish, this}; }
};

// A world on `threads` threads (fixed or the policy's), through the host's tasks when given.
World profiled_world(int threads, bool fixed, ThreadPerTask* host) {
  WorldSettings s;
  s.threads = threads;
  s.fixed_threads = fixed;
  World world(s);
  if (host != nullptr) world.set_task_callbacks(host->callbacks());
  world.set_profiling(true);
  return world;
}

struct ChainRun {
  std::uint64_t hash;
  int steps_on_two_threads;
};

// A soft chain of distance joints with limit rows and a hub whose joints overflow the colours:
// every stage's threaded path.
ChainRun run_chain(int threads, bool fixed, ThreadPerTask* host) {
  World world = profiled_world(threads, fixed, host);
  scenes::ChainOptions o;
  o.links = 600;
  o.joint = scenes::ChainJoint::Distance;
  o.spring = Spring::soft(15.0, 0.3);
  const scenes::ChainScene chain = scenes::build_chain(world, o);
  BodyDef hub_def;
  hub_def.position = {0.0, 2.0, 0.0};
  hub_def.mass = 100.0;
  const BodyId hub = world.create_body(hub_def);
  for (std::size_t i = 0; i < 30; ++i) {  // more than the colours: an overflow set
    DistanceJointDef d;
    d.body_a = hub;
    d.body_b = chain.links[0][i * 20];
    d.spring = Spring::free();
    d.min_length = 0.5;
    d.max_length = 4.0 + 0.1 * static_cast<double>(i);
    world.create_distance_joint(d);
  }
  ChainRun r{0, 0};
  for (int i = 0; i < 40; ++i) {
    world.step(1.0 / 60.0);
    r.steps_on_two_threads += world.last_step_profile().threads == 2 ? 1 : 0;
  }
  r.hash = world.state_hash();
  return r;
}

TEST(Threads, HostTaskCallbacksGiveTheSameWorldAsOpenMPAndOneThread) {
  const ChainRun one = run_chain(1, true, nullptr);
  const ChainRun openmp = run_chain(2, true, nullptr);
  ThreadPerTask host;
  const ChainRun hosted = run_chain(2, true, &host);
  EXPECT_EQ(openmp.hash, one.hash);
  EXPECT_EQ(hosted.hash, one.hash);
  // The scene is far below the adaptive policy's 4,096 bodies and joints: only the forced
  // count puts it on two threads, every step, each step enqueuing one worker.
  EXPECT_EQ(one.steps_on_two_threads, 0);
  EXPECT_EQ(openmp.steps_on_two_threads, 40);
  EXPECT_EQ(hosted.steps_on_two_threads, 40);
  EXPECT_EQ(host.enqueued.load(), 40);
}

// 4,200 boxes on the ground, each with its manifold: from 4,096 manifolds a step checks them
// on its threads before it runs the stages, so it enqueues its worker twice. The second
// thread lays them out beside the checks on the first two steps; from the third, the layout
// inputs holding, every thread checks and compares them, and the layout is kept.
struct BoxesRun {
  std::uint64_t hash;
  int checked_on_two, laid_out_beside, kept;
  int ran_on_two = 0;  // steps whose stages ran on two threads
  long switches = 0;   // the adaptive policy's, after the last step
};

struct BoxesOptions {
  // Each step is called from one thread of an OpenMP parallel region of two, as a host that
  // steps worlds in its own parallel loop would; the caller has left nesting off, so the
  // step's team comes out as one thread.
  bool inside_region = false;
  bool fixed = true;  // the thread count fixed, or the adaptive policy's
  int steps = 5;
};

BoxesRun run_boxes(int threads, ThreadPerTask* host, const BoxesOptions& o = {}) {
  World world = profiled_world(threads, o.fixed, host);
  const BodyId ground = test::add_ground(world);
  std::vector<BodyId> boxes;
  for (int i = 0; i < 4200; ++i) {
    boxes.push_back(test::add_box(world, {1.5 * i, 0.5 + 0.01 * (i % 5), 0.0}, 1.0 + i % 3,
                                  test::kUnitCubeHalf));
  }
  BoxesRun r{};
  for (int step = 0; step < o.steps; ++step) {
    std::vector<ContactManifold> c;
    for (BodyId b : boxes) c.push_back(test::box_on_ground(world, ground, b, test::kUnitCubeHalf));
    if (o.inside_region) {
#pragma omp parallel num_threads(2)
#pragma omp single
      world.step(1.0 / 60.0, c);
    } else {
      world.step(1.0 / 60.0, c);
    }
    r.checked_on_two += world.last_step_profile().check_threads == 2 ? 1 : 0;
    r.laid_out_beside += world.last_step_profile().contact_load_beside_checks ? 1 : 0;
    r.kept += world.last_step_profile().contact_layout_kept ? 1 : 0;
    r.ran_on_two += world.last_step_profile().threads == 2 ? 1 : 0;
  }
  r.switches = world.last_step_profile().thread_switches;
  r.hash = world.state_hash();
  return r;
}

TEST(Threads, HostTasksCheckManyContactsAsOpenMPDoes) {
  const BoxesRun one = run_boxes(1, nullptr);
  const BoxesRun openmp = run_boxes(2, nullptr);
  ThreadPerTask host;
  const BoxesRun hosted = run_boxes(2, &host);
  EXPECT_EQ(openmp.hash, one.hash);
  EXPECT_EQ(hosted.hash, one.hash);
  EXPECT_EQ(one.checked_on_two, 0);
  EXPECT_EQ(openmp.checked_on_two, 5);
  EXPECT_EQ(hosted.checked_on_two, 5);
  EXPECT_EQ(openmp.laid_out_beside, 2);
  EXPECT_EQ(hosted.laid_out_beside, 2);
  EXPECT_EQ(openmp.kept, 3);
  EXPECT_EQ(hosted.kept, 3);
  EXPECT_EQ(one.kept, 4);
  EXPECT_EQ(openmp.ran_on_two, 5);
  EXPECT_EQ(hosted.ran_on_two, 5);
  EXPECT_EQ(host.enqueued.load(), 10);  // the checks' worker and the stages' worker, per step
}

// The profile counts the threads that ran a step, not those asked for: inside a parallel
// region with nesting off, OpenMP gives the step a team of one, and the checks and the stages
// say so, and the result is the one thread's.
TEST(Threads, AStepGivenFewerThreadsThanAskedReportsThoseItRanOn) {
  const BoxesRun one = run_boxes(1, nullptr);
  const int levels = omp_get_max_active_levels();
  omp_set_max_active_levels(1);
  const BoxesRun nested = run_boxes(2, nullptr, {.inside_region = true});
  omp_set_max_active_levels(levels);
  EXPECT_EQ(nested.hash, one.hash);
  EXPECT_EQ(nested.checked_on_two, 0);
  EXPECT_EQ(nested.laid_out_beside, 0);
  EXPECT_EQ(nested.ran_on_two, 0);
}

// Nor does such a step teach the adaptive policy what two threads cost: it is not timed. Out
// of a region the policy's first block (the step that lays out, a warm-up and four timed steps
// on two threads) ends by switching to one thread to measure it; inside one, with every step
// given a team of one, no block completes and it never switches.
TEST(Threads, AStepGivenFewerThreadsThanAskedTeachesThePolicyNothing) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one core: nothing to share";
  const BoxesRun outside = run_boxes(2, nullptr, {.fixed = false, .steps = 8});
  EXPECT_GE(outside.switches, 1);  // then back, or not, as the times say
  const int levels = omp_get_max_active_levels();
  omp_set_max_active_levels(1);
  const BoxesRun nested =
      run_boxes(2, nullptr, {.inside_region = true, .fixed = false, .steps = 8});
  omp_set_max_active_levels(levels);
  EXPECT_EQ(nested.switches, 0);
  EXPECT_EQ(nested.ran_on_two, 0);
  EXPECT_EQ(nested.hash, outside.hash);
}

TEST(Threads, AdaptivePolicyDecidesUnlessTheCountIsFixed) {
  ThreadPerTask host;
  const ChainRun adaptive = run_chain(2, false, &host);
  EXPECT_EQ(adaptive.steps_on_two_threads, 0);  // too small to share
  EXPECT_EQ(host.enqueued.load(), 0);
  EXPECT_EQ(run_chain(2, true, &host).steps_on_two_threads, 40);
}

TEST(Threads, TaskCallbacksComeInPairs) {
  World world;
  const std::uint64_t before = world.state_hash();
  TaskCallbacks half;
  half.enqueue = &ThreadPerTask::enqueue;
  try {
    world.set_task_callbacks(half);
    ADD_FAILURE() << "accepted enqueue without finish";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.field(), "TaskCallbacks.finish");
  }
  EXPECT_EQ(world.state_hash(), before);
  world.set_task_callbacks({});  // back to OpenMP
  world.step(1.0 / 60.0);
}

}  // namespace
}  // namespace softstep
