// The sender's log in the database, kept from the transmitter's progress events.
//
// TransmissionRecord is the pure part: it turns each event into the rows to write, inserted
// or updated by id (a command: queued, transmitting, then its outcome; an attempt: when its
// chord started, then when it ended, the answer and when it was heard). StoreRecorder is
// the ProgressObserver that writes those rows through store::Store.
#pragma once

#include <map>
#include <mutex>
#include <string>
#include <variant>
#include <vector>

#include "progress_observer.h"
#include "store.h"

namespace dtmf::server {

class TransmissionRecord {
 public:
  using Row = std::variant<store::CommandRow, store::FrameAttemptRow>;

  explicit TransmissionRecord(std::string host) : host_(std::move(host)) {}

  // The rows this event creates or changes, in the order to write them.
  std::vector<Row> on_event(const Job& job, const ProgressEvent& event);

 private:
  // The command's row, begun now if this record has not seen it queued.
  store::CommandRow& command_of(const Job& job, store::WallTime requested_at);

  std::string host_;  // this sender, in every command row
  // What is written so far of each command not yet ended, and of its attempt on air.
  std::map<std::string, store::CommandRow> commands_;
  std::map<std::string, store::FrameAttemptRow> attempts_;
};

class StoreRecorder final : public ProgressObserver {
 public:
  StoreRecorder(store::Store& store, std::string host) : store_(store), record_(std::move(host)) {}
  void observe(const Job& job, const ProgressEvent& event) override;

 private:
  store::Store& store_;
  std::mutex mutex_;  // Queued comes from callers' threads, the rest from the worker
  TransmissionRecord record_;
};

}  // namespace dtmf::server
