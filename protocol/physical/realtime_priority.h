// Audio threads ahead of the rest of the machine: real-time scheduling for the threads that
// feed a loudspeaker or drain a microphone.
//
// A blocking audio stream holds a few tens of milliseconds (docs/protocol.md §7). A thread
// that is not scheduled for longer than that makes the loudspeaker run dry mid-chord, or the
// microphone drop samples: on a 2-core machine under `stress-ng --cpu 2` the sender's chords
// were stretched by 170 ms of silence and the robot heard one seed chord twice. So the audio
// threads ask for SCHED_FIFO at a low real-time priority (below PulseAudio's default of 5, so
// the sound server still mixes first); where that is not allowed (no CAP_SYS_NICE, no
// RLIMIT_RTPRIO) they ask for a raised nice level instead, and else run as they are.
#pragma once

#include <string>

namespace dtmf::physical {

enum class ThreadPriority { Realtime, Raised, Normal };

// Raises the calling thread as far as allowed. Returns what it got; `why` (if given) says
// how and, if not real-time, what to do about it.
ThreadPriority raise_audio_thread_priority(std::string* why = nullptr);

// Raised for its lifetime, then back to what the thread had: open audio devices inside one.
// A sound library's own threads (ALSA's PulseAudio plugin moves every block through one)
// are made when a device opens and inherit their creator's scheduling; left at normal
// priority, that thread was starved under load and a chord still came out with 300 ms of
// silence in it although the thread writing it was real-time.
class AudioPriorityScope {
 public:
  AudioPriorityScope();
  ~AudioPriorityScope();
  AudioPriorityScope(const AudioPriorityScope&) = delete;
  AudioPriorityScope& operator=(const AudioPriorityScope&) = delete;

 private:
  int policy_ = 0;
  int priority_ = 0;
  int nice_ = 0;
};

}  // namespace dtmf::physical
