// Reliability layer: a sender's carrier sense — whether anyone else sounds on the air.
//
// The sender's microphone hears its own loudspeaker, its robots' answers, and every other
// sender and robot in the room. This keeps the level of each block the microphone gives
// (dBFS, block_level_dbfs) against the room's noise floor, and calls a block *busy* when it,
// and the level smoothed over the last kFloorSmoothMs, stand kBusyOverFloorDb over that
// floor (a sound lasts; a block of noise may pass the mark alone), and it is not the
// sender's own sound:
// - its frame, from its start until it ended (own_begin, frame_ended);
// - that frame's reverberant tail, and after the exchange its answer's: blocks that do not
//   rise kBusyOverFloorDb over the quietest the tail's envelope has been since, until the
//   envelope falls into the noise (kTailEndMarginDb under the floor's busy mark), for at most
//   kOwnTailMaxMs. A tail only falls; another sender's frame begins with a rise. The
//   envelope is the loudest block of the last kFloorSmoothMs, because a tone's decay in a
//   room beats: single 5 ms blocks of it dip 10 dB and more under it and come back
//   (carrier_sense_rooms_test.cpp). While we wait for our answer, single blocks count: a
//   frame and its answer may leave less than 20 ms between them, and an envelope that never
//   fell would hide a quieter sender in every wait;
// - its robot's answer. The microphone keeps listening while the sender waits for it, so
//   that a sender that is never silent between its exchanges still hears the others in its
//   waits, but a block it hears busy there stays provisional until the exchange ends
//   (own_end) and is dropped if it falls within the answer's sound, which only then is known.
//
// The floor is the quietest the air has been over the last kFloorWindowMs, our own sound
// left out ("minimum statistics", R. Martin, IEEE Trans. Speech Audio Process. 9(5), 2001):
// the lowest of the block levels smoothed over kFloorSmoothMs. Steady noise (a fan, a
// simulated room's pink noise) becomes the floor; a block of digital silence among it (an
// underrun) lowers the smoothed level by a decibel, not to silence; another's frames do not
// lift it while the air falls quiet for kFloorSmoothMs once in kFloorWindowMs (two senders'
// frames do at each handover: air_access.h). After a window of nothing but our own sound,
// the floor stays where it was.
// Pure logic: the caller says when each block ended (any monotonic millisecond clock) and
// when its own exchanges began and ended. Thresholds follow the habit of spandsp's dtmf.c:
// named, with their units.
#pragma once

#include <cstddef>
#include <deque>
#include <optional>
#include <span>
#include <vector>

namespace dtmf::reliability {

inline constexpr double kBusyOverFloorDb = 10;    // a block this far over the floor is a sound
inline constexpr double kOwnTailMaxMs = 2000;     // a tail held longer than this is not ours (RT60 3 s)
inline constexpr double kOwnLatencyMs = 100;      // capture latency: our sound may still arrive
inline constexpr double kTailEndMarginDb = 6;     // our tail ends this far under the busy mark
inline constexpr double kFloorWindowMs = 30'000;  // the floor: the quietest of the last 30 s
inline constexpr double kFloorSmoothMs = 20;      // ... of levels smoothed over 20 ms
inline constexpr double kSilenceDbfs = -120;      // digital silence reads as this level

// The mean power of `samples` in dB relative to a full-scale sine's (a full-scale sine is
// 0 dBFS); kSilenceDbfs for silence or no samples.
double block_level_dbfs(std::span<const float> samples);

// A stretch of time, in the caller's milliseconds.
struct AirSpan {
  double from_ms = 0, to_ms = 0;
};

// Where our robot's answer to a frame that ended at `frame_end_ms` sounds (or would have),
// for CarrierSense::own_end: `answer_ms` long, `delay_ms` after the frame (as its last
// answer came), with kOwnLatencyMs either side. Before a robot has answered at all, its
// answer may begin anywhere up to `max_delay_ms` after the frame (its profile's
// ack_timeout_ms − chord_ms), and the whole of that is its own: an answer heard but not read
// (too weak, or garbled by the room) is still no other sender's.
AirSpan own_answer_span(double frame_end_ms, std::optional<double> delay_ms, double max_delay_ms, double answer_ms);

class CarrierSense {
 public:
  // Our frame begins: what is heard is ours until frame_ended().
  void own_begin(double at_ms);
  // Our frame ended; we wait for its answer, and listen meanwhile.
  void frame_ended(double at_ms);
  // Our exchange ended (its answer came, or the wait for it ended); `answer`: when our
  // robot's answer sounded, if it did (busy blocks heard within it were that answer).
  void own_end(double at_ms, std::optional<AirSpan> answer = std::nullopt);
  // One microphone block of `level_dbfs`, which ended at `end_ms`.
  void hear(double level_dbfs, double end_ms);
  // The sender's ear read a robot's answer that ended at `end_ms` (it decodes every robot's
  // answers in the profiles it knows). Outside our own exchange, it was another's: that
  // exchange is over, and nobody waits on the air for it. What follows is its tail until a
  // sound rises kBusyOverFloorDb over the quietest the tail's envelope has been (as for our
  // own tail): a new frame.
  void answer_read(double end_ms);
  // The sender's ear read, during our exchange, an answer from a robot that is none of ours
  // (fast answers name their robot), ending at `end_ms`. Another's exchange went on under
  // ours, where the microphone takes every sound for our own: two senders that started
  // together and then send back to back hide each other's frames this way for as long as
  // they run (neither ever hears the air busy). It counts as another's sound at `end_ms`, so
  // the room is shared and our next frame defers and listens.
  void answer_masked(double end_ms);

  // The last block heard busy (another's sound), if any; blocks of our wait count once it ended.
  std::optional<double> last_busy_ms() const { return last_busy_ms_; }
  // How far that block stood over the room's floor then (dB), for the operator; and whether
  // it was no block but another's robot's answer read under our exchange (answer_masked).
  double last_busy_over_floor_db() const { return last_busy_over_floor_db_; }
  bool last_busy_masked() const { return last_busy_masked_; }
  // Whether the last block heard was busy.
  bool busy_now() const { return busy_now_; }
  // Since when the air has been quiet: no sound of ours, its tail fallen into the noise, and
  // none of another's; nothing while it is not.
  std::optional<double> quiet_since_ms() const { return quiet_since_ms_; }
  // Whether our frame sounds, or we wait for its answer.
  bool own_on() const { return own_on_ || waiting_; }
  // When our last exchange ended; nothing before the first.
  std::optional<double> own_ended_ms() const { return own_ended_ms_; }
  // When another's exchange ended in an answer we read, if nothing but that answer's tail
  // has sounded since.
  std::optional<double> answered_exchange_ms() const { return answer_tail_open_ ? others_answer_ms_ : std::nullopt; }
  double floor_dbfs() const { return floor_dbfs_; }
  std::size_t busy_blocks() const { return busy_blocks_; }
  // How many answers read were another's (answer_read outside our exchange).
  std::size_t others_answers() const { return others_answers_; }
  // How many answers another's robot gave were read under our own exchange (answer_masked).
  std::size_t masked_answers() const { return masked_answers_; }

 private:
  bool ours(double level_dbfs, double end_ms);
  // Follows the floor with a non-own block; returns the level smoothed over kFloorSmoothMs.
  double follow_floor(double level_dbfs, double end_ms);
  void tail_from(double at_ms);
  void follow_answer_tail(double level_dbfs, double end_ms);

  bool own_on_ = false;   // our frame sounds
  bool waiting_ = false;  // ... it ended, and we wait for its answer
  std::optional<double> own_ended_ms_;
  std::optional<double> tail_from_ms_;                 // our last sound ended here
  std::deque<std::pair<double, double>> tail_recent_;  // (end_ms, level) of its last kFloorSmoothMs
  double tail_min_dbfs_ = 0;                           // the quietest since (envelope; while waiting, a block)
  // Busy blocks heard while we wait: (end_ms, dB over the floor).
  std::vector<std::pair<double, double>> provisional_;
  std::optional<double> last_busy_ms_;
  double last_busy_over_floor_db_ = 0;
  bool last_busy_masked_ = false;
  bool busy_now_ = false;
  std::optional<double> quiet_since_ms_;
  std::optional<double> others_answer_ms_;
  bool answer_tail_open_ = false;  // since it, only its tail
  std::size_t others_answers_ = 0;
  std::size_t masked_answers_ = 0;
  double answer_tail_min_dbfs_ = 0;
  std::deque<std::pair<double, double>> others_recent_;  // (end_ms, level) of the last kFloorSmoothMs not ours
  std::size_t busy_blocks_ = 0;
  std::optional<double> smoothed_power_;     // mean-square, relative to a full-scale sine's
  std::optional<double> last_end_ms_;        // the last block not ours
  std::optional<double> last_block_end_ms_;  // the last block
  // (end_ms, smoothed level) of the last 10 s, levels rising from front to back: the front
  // is the floor (a monotonic queue, so each block costs O(1)).
  std::deque<std::pair<double, double>> minima_;
  double floor_dbfs_ = kSilenceDbfs;
};

}  // namespace dtmf::reliability
