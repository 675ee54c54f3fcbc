// Audio threads ahead of the rest of the machine: real-time scheduling for the threads that
// feed a loudspeaker, a raised nice level for the threads that drain a microphone.
//
// A blocking audio stream holds a few tens of milliseconds (docs/protocol.md §7). A thread
// that is not scheduled for longer than that makes the loudspeaker run dry mid-chord, or the
// microphone drop samples: on a 2-core machine under `stress-ng --cpu 2` the sender's chords
// were stretched by 170 ms of silence and the robot heard one seed chord twice. So the
// threads that play ask for SCHED_FIFO at a low real-time priority; where that is not allowed
// (no CAP_SYS_NICE, no RLIMIT_RTPRIO) they ask for a raised nice level instead, and else run
// as they are.
//
// The ranks, highest first: PulseAudio's I/O threads (SCHED_RR 5), the sound library's own
// threads (FIFO 4: ALSA's PulseAudio plugin moves every block through one, made when a device
// opens inside an AudioPriorityScope), our threads that play (FIFO 3), our threads that
// record (nice −11, not real-time). A thread must never outrank the thread it waits for:
// PortAudio's ALSA read polls in a loop while the plugin's thread has not moved the samples
// yet, and at equal FIFO rank the poller kept that thread off the CPU for good — with 20
// agents on 2 cores, two agents' readers spun at 94 % and every other process starved for
// ten minutes. Recording is forgiving (the sound server buffers what was captured), so its
// reader stays out of real time altogether.
#pragma once

#include <string>

namespace dtmf::physical {

enum class ThreadPriority { Realtime, Raised, Normal };

// For a thread that plays: raises it as far as allowed. Returns what it got; `why` (if given)
// says how and, if not real-time, what to do about it.
ThreadPriority raise_audio_thread_priority(std::string* why = nullptr);

// For a thread that records: a raised nice level, never real time (see above).
ThreadPriority raise_capture_thread_priority(std::string* why = nullptr);

// Raised for its lifetime (to the sound library's rank), then back to what the thread had:
// open audio devices inside one. A sound library's own threads are made when a device opens
// and inherit their creator's scheduling; left at normal priority, that thread was starved
// under load and a chord still came out with 300 ms of silence in it although the thread
// writing it was real-time.
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
