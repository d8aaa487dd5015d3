#pragma once
/// @file core/tbb_sanitizer.hpp
/// What ThreadSanitizer must be told about TBB, used by core/parallel.hpp;
/// compiled in ThreadSanitizer builds only (VM_TSAN_TBB).
///
/// Debian's libtbb is not instrumented, so TSan sees neither how TBB hands a
/// task to another thread nor how it waits for the tasks to end. Two things
/// make up for it:
/// - happens-before edges for what oneTBB's algorithms guarantee: everything
///   the caller did before a parallel call happens-before every task of that
///   call (a loop body, a reduction's join, an invoked function), and every
///   task happens-before the call's return (__tsan_release / __tsan_acquire);
/// - TSan records no memory access of a thread while it runs TBB's own code,
///   only those of our tasks and of the code around the calls. TBB works on
///   its task objects and on the caller's stack after a task has ended (it
///   counts the finished tasks down there), which no edge of ours can come
///   after; recorded, those accesses show up as races with whatever reuses
///   that memory later. TBB's code is TBB's to check, like the library it is
///   part of. The tasks' code, and so every race of ours, is still checked.
/// The edges come from the public interface sanitizer/tsan_interface.h, the
/// recording switch from the runtime's dynamic-annotation interface
/// (AnnotateIgnoreReadsBegin...): no suppression hides a report.

#if defined(__SANITIZE_THREAD__)
#define VM_TSAN_TBB 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define VM_TSAN_TBB 1
#endif
#endif

#ifdef VM_TSAN_TBB

#include <sanitizer/tsan_interface.h>

#include <tuple>
#include <type_traits>
#include <utility>

namespace vm::detail::tsan {

/// Turns TSan's recording of this thread's memory accesses on or off and
/// returns whether it was on. Recording is on in every thread but TBB's
/// workers, which turn it off when they join the arena, before their first task.
bool set_recording(bool on);

template <class F> class Task;

/// One parallel call: alive while TBB runs it, on the caller's stack. Its two
/// addresses are the synchronisation objects of the call's edges.
class ParallelCall {
public:
  /// Releases `start_`, then stops recording: TBB's code runs next.
  ParallelCall() : was_recording_(set_recording(false)) { __tsan_release(&start_); }
  /// Every task has released `done_` by now; recording is back as it was.
  ~ParallelCall() {
    __tsan_acquire(&done_);
    set_recording(was_recording_);
  }
  ParallelCall(const ParallelCall&) = delete;
  ParallelCall& operator=(const ParallelCall&) = delete;

  /// `f` as a task of this call, to hand to TBB instead of `f`.
  template <class F> Task<F> task(const F& f) const { return Task<F>(f, *this); }

private:
  template <class F> friend class Task;

  mutable char start_ = 0, done_ = 0; // only their addresses matter
  bool was_recording_;
};

/// A function TBB calls as a task of a ParallelCall: recorded, and between the
/// call's edges. Two pointers, so that TBB's copies of it are cheap.
template <class F> class Task {
public:
  Task(const F& f, const ParallelCall& call) : f_(&f), call_(&call) {}

  template <class... Args> decltype(auto) operator()(Args&&... args) const {
    // The arguments (ranges, partial results) live in TBB's task objects and
    // are copied before recording starts, like the two pointers.
    const F& f = *f_;
    const ParallelCall& call = *call_;
    std::tuple<std::decay_t<Args>...> copies(std::forward<Args>(args)...);
    const Scope scope(call);
    return std::apply(f, copies);
  }

private:
  /// Recording on and the start edge taken; the done edge given on the way
  /// out, exceptions included, and recording back as TBB had it.
  class Scope {
  public:
    explicit Scope(const ParallelCall& call) : call_(call), was_recording_(set_recording(true)) {
      __tsan_acquire(&call_.start_);
    }
    ~Scope() {
      __tsan_release(&call_.done_);
      set_recording(was_recording_);
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

  private:
    const ParallelCall& call_;
    bool was_recording_;
  };

  const F* f_;
  const ParallelCall* call_;
};

} // namespace vm::detail::tsan

#endif
