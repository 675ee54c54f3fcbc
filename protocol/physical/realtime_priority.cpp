#include "physical/realtime_priority.h"

#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace dtmf::physical {

namespace {
// SCHED_FIFO priorities (1..99), below PulseAudio's realtime-priority of 5, whose I/O threads
// must mix first; the ranks and why they differ are in the header.
constexpr int kSoundLibraryFifoPriority = 4;
constexpr int kPlaybackFifoPriority = 3;
// PulseAudio's high-priority nice level, for when real time is not allowed or not wanted.
constexpr int kAudioNiceLevel = -11;

int thread_id() { return static_cast<int>(::syscall(SYS_gettid)); }

bool raise_nice(std::string* why, const std::string& because) {
  if (::setpriority(PRIO_PROCESS, static_cast<id_t>(thread_id()), kAudioNiceLevel) != 0) return false;
  if (why) *why = "nice " + std::to_string(kAudioNiceLevel) + because;
  return true;
}

// FIFO at `fifo_priority` where allowed, else the raised nice level, else nothing.
ThreadPriority raise(int fifo_priority, std::string* why) {
  sched_param param{};
  param.sched_priority = fifo_priority;
  const int fifo_error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
  if (fifo_error == 0) {
    if (why) *why = "real-time (SCHED_FIFO " + std::to_string(fifo_priority) + ")";
    return ThreadPriority::Realtime;
  }
  // setpriority on a thread id changes that thread only (Linux).
  if (raise_nice(why, std::string(" (real time refused: ") + std::strerror(fifo_error) + ")"))
    return ThreadPriority::Raised;
  if (why) {
    *why = std::string("normal priority (real time refused: ") + std::strerror(fifo_error) +
           "); under load the audio may drop out: allow real-time scheduling (systemd LimitRTPRIO=4, or "
           "an rtprio line in /etc/security/limits.d, or CAP_SYS_NICE)";
  }
  return ThreadPriority::Normal;
}
}  // namespace

ThreadPriority raise_audio_thread_priority(std::string* why) { return raise(kPlaybackFifoPriority, why); }

ThreadPriority raise_capture_thread_priority(std::string* why) {
  if (raise_nice(why, "")) return ThreadPriority::Raised;
  if (why) *why = std::string("normal priority (a raised nice level refused: ") + std::strerror(errno) + ")";
  return ThreadPriority::Normal;
}

AudioPriorityScope::AudioPriorityScope() {
  sched_param param{};
  pthread_getschedparam(pthread_self(), &policy_, &param);
  priority_ = param.sched_priority;
  errno = 0;
  nice_ = ::getpriority(PRIO_PROCESS, static_cast<id_t>(thread_id()));
  raise(kSoundLibraryFifoPriority, nullptr);
}

AudioPriorityScope::~AudioPriorityScope() {
  sched_param param{};
  param.sched_priority = priority_;
  pthread_setschedparam(pthread_self(), policy_, &param);
  ::setpriority(PRIO_PROCESS, static_cast<id_t>(thread_id()), nice_);
}

}  // namespace dtmf::physical
