// Running a step's threads on the host's job system instead of OpenMP (World::set_task_callbacks),
// the way Box2D v3 takes an enqueue / finish pair. The results are bit-identical to OpenMP's and
// to one thread's: the work is split the same way whoever runs it.
#pragma once

namespace softstep {

struct TaskCallbacks {
  // One worker of a step: call task(worker, task_context) once, on any thread.
  using Task = void (*)(int worker, void* task_context);
  // Starts task(worker, task_context) on one of the host's threads and returns a handle that
  // finish() is later given (nullptr is a valid handle). The step enqueues workers 1 .. n-1
  // (n: the step's thread count, WorldSettings::threads), runs worker 0 on the calling thread,
  // then calls finish for each handle. The workers wait for one another at barriers, so the
  // host must run them all at the same time as the caller: a job system that runs the task
  // inline in enqueue, or queues it behind busy workers, deadlocks the step. Give softstep at
  // most as many threads as the host has free workers, plus the caller. A step with 4,096
  // contact manifolds or more does this twice: for the contact checks, then for the stages.
  void* (*enqueue)(Task task, int worker, void* task_context, void* user_context) = nullptr;
  // Returns once the task of that handle has returned.
  void (*finish)(void* user_task, void* user_context) = nullptr;
  void* user_context = nullptr;  // passed back to enqueue and finish
};

}  // namespace softstep
