/// @file core/tbb_sanitizer.cpp
/// The per-thread recording switch of core/tbb_sanitizer.hpp, and the
/// observer that turns it off in TBB's workers. Empty outside ThreadSanitizer builds.

#include "core/tbb_sanitizer.hpp"

#ifdef VM_TSAN_TBB

#include <tbb/task_scheduler_observer.h>

// The TSan runtime's dynamic-annotation interface (its "ignore" annotations).
extern "C" {
void AnnotateIgnoreReadsBegin(const char* file, int line);
void AnnotateIgnoreReadsEnd(const char* file, int line);
void AnnotateIgnoreWritesBegin(const char* file, int line);
void AnnotateIgnoreWritesEnd(const char* file, int line);
}

namespace vm::detail::tsan {

namespace {

/// This thread's switch. It is back on when the thread ends: TSan fails a
/// thread that ends with its accesses ignored (a worker's switch is off then).
struct Recording {
  bool on = true;
  ~Recording() { set_recording(true); }
};
thread_local Recording recording;

/// Turns recording off in each TBB worker as it joins the arena, before it
/// runs TBB's code for its first task.
class WorkerObserver final : public tbb::task_scheduler_observer {
public:
  WorkerObserver() { observe(true); }
  void on_scheduler_entry(bool is_worker) override {
    if (is_worker) set_recording(false);
  }
};

// Made as the library loads, on the main thread, so that it observes the
// arena every parallel call of the main thread runs in, before the first one;
// never destroyed, as TBB may still be running workers when statics die.
const WorkerObserver* const observer = new WorkerObserver;

} // namespace

bool set_recording(bool on) {
  const bool was = recording.on;
  if (on == was) return was;
  if (on) {
    AnnotateIgnoreReadsEnd(__FILE__, __LINE__);
    AnnotateIgnoreWritesEnd(__FILE__, __LINE__);
  } else {
    AnnotateIgnoreReadsBegin(__FILE__, __LINE__);
    AnnotateIgnoreWritesBegin(__FILE__, __LINE__);
  }
  recording.on = on;
  return was;
}

} // namespace vm::detail::tsan

#endif
