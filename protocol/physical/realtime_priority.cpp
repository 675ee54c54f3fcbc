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
// SCHED_FIFO priority 1..99; PulseAudio's realtime-priority defaults to 5 and its mixing
// thread must stay ahead of its clients.
constexpr int kAudioFifoPriority = 4;
// PulseAudio's high-priority nice level, for when real time is not allowed.
constexpr int kAudioNiceLevel = -11;
}  // namespace

ThreadPriority raise_audio_thread_priority(std::string* why) {
  sched_param param{};
  param.sched_priority = kAudioFifoPriority;
  const int fifo_error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
  if (fifo_error == 0) {
    if (why) *why = "real-time (SCHED_FIFO " + std::to_string(kAudioFifoPriority) + ")";
    return ThreadPriority::Realtime;
  }
  // setpriority on a thread id changes that thread only (Linux).
  const auto tid = static_cast<id_t>(::syscall(SYS_gettid));
  if (::setpriority(PRIO_PROCESS, tid, kAudioNiceLevel) == 0) {
    if (why)
      *why = "nice " + std::to_string(kAudioNiceLevel) + " (real time refused: " + std::strerror(fifo_error) + ")";
    return ThreadPriority::Raised;
  }
  if (why) {
    *why = std::string("normal priority (real time refused: ") + std::strerror(fifo_error) +
           "); under load the audio may drop out: allow real-time scheduling (systemd LimitRTPRIO=5, or "
           "an rtprio line in /etc/security/limits.d, or CAP_SYS_NICE)";
  }
  return ThreadPriority::Normal;
}

AudioPriorityScope::AudioPriorityScope() {
  sched_param param{};
  pthread_getschedparam(pthread_self(), &policy_, &param);
  priority_ = param.sched_priority;
  errno = 0;
  nice_ = ::getpriority(PRIO_PROCESS, static_cast<id_t>(::syscall(SYS_gettid)));
  raise_audio_thread_priority();
}

AudioPriorityScope::~AudioPriorityScope() {
  sched_param param{};
  param.sched_priority = priority_;
  pthread_setschedparam(pthread_self(), policy_, &param);
  ::setpriority(PRIO_PROCESS, static_cast<id_t>(::syscall(SYS_gettid)), nice_);
}

}  // namespace dtmf::physical
