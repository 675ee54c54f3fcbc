// TeleopReactor's reactions: the slot, the first message, the client's messages, writes done
// and the cancel. Each notes what came and runs the step (teleop_stream_step.cpp).
#include "teleop_stream.h"

#include "request_validation.h"

namespace dtmf::server {

TeleopSlot::TeleopSlot(std::mutex& mutex, std::weak_ptr<TeleopSession>& holder,
                       const std::shared_ptr<TeleopSession>& session)
    : mutex_(mutex), holder_(holder) {
  std::lock_guard lock(mutex_);
  if (!holder_.expired()) return;
  holder_ = session;
  held_ = true;
}

TeleopSlot::~TeleopSlot() {
  if (!held_) return;
  std::lock_guard lock(mutex_);
  holder_.reset();
}

TeleopReactor::TeleopReactor(Transmitter& transmitter, TeleopOpener open)
    : transmitter_(transmitter), open_(std::move(open)) {}

TeleopReactor* TeleopReactor::start(Transmitter& transmitter, TeleopOpener open) {
  auto reactor = std::shared_ptr<TeleopReactor>(new TeleopReactor(transmitter, std::move(open)));
  TeleopReactor* r = reactor.get();
  r->self_ = reactor;
  r->steps_.emplace(std::weak_ptr<void>(reactor), [r] { r->step(); });
  r->StartRead(&r->request_);
  return r;
}

void TeleopReactor::OnReadDone(bool ok) {
  bool is_open = false;
  {
    std::lock_guard lock(mutex_);
    is_open = opened_;
    if (!ok && !is_open) closed_unopened_ = true;  // closed before it asked for anything
  }
  if (!ok) {
    if (is_open) session_->end_stream();  // the client half-closed, or it is gone
    return steps_->run();
  }
  if (!is_open) return opened(request_);
  request_.set_lease_s(setup_.first_lease_s);  // the stream's lease is the first message's
  try {
    session_->set_target(setup_.target_of(request_), steady_s());
  } catch (const RequestError& e) {
    {
      std::lock_guard lock(mutex_);
      refused_ = e.status();
    }
    session_->end_stream();
    return steps_->run();
  }
  if (!session_->halted()) StartRead(&request_);
  steps_->run();  // a new target may be due now
}

void TeleopReactor::opened(const v1::TeleopRequest& first) {
  auto opening = open_(first);
  if (auto* refused = std::get_if<grpc::Status>(&opening)) {
    {
      std::lock_guard lock(mutex_);
      refused_ = *refused;
    }
    return steps_->run();
  }
  auto& o = std::get<TeleopOpened>(opening);
  session_ = std::move(o.session);
  slot_ = std::move(o.slot);
  setup_ = std::move(o.setup);
  session_->set_target(setup_.first_target, steady_s());
  std::weak_ptr<TeleopReactor> told = self_;
  session_->on_halt([told] {
    if (auto r = told.lock()) r->steps_->run_soon();  // on the halting RPC's thread: hop
  });
  {
    std::lock_guard lock(mutex_);
    opened_ = true;
  }
  StartRead(&request_);
  steps_->run();
}

void TeleopReactor::OnWriteDone(bool ok) {
  {
    std::lock_guard lock(mutex_);
    writing_ = false;
    if (!ok) cancelled_ = true;  // nobody reads any more
  }
  steps_->run();
}

void TeleopReactor::OnCancel() {
  {
    std::lock_guard lock(mutex_);
    cancelled_ = true;
  }
  steps_->run();
}

void TeleopReactor::OnDone() {
  slot_.reset();  // if the stream ended before it was opened, the slot the opening took
  self_.reset();
}

}  // namespace dtmf::server
