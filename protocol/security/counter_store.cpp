#include "security/counter_store.h"

#include <algorithm>
#include <stdexcept>

#include "security/freshness.h"

namespace dtmf::security {

std::uint64_t MemoryCounterStore::next_counter() { return next_counter_from(0); }

std::uint64_t MemoryCounterStore::next_counter_from(std::uint64_t at_least) {
  std::lock_guard lock(mutex_);
  next_ = std::max(next_, at_least);
  if (next_ >= kCounterLimit) throw std::runtime_error("the freshness counter is used up: rotate the key");
  return next_++;
}

std::optional<std::uint64_t> MemoryCounterStore::last_confirmed() const {
  std::lock_guard lock(mutex_);
  return last_confirmed_;
}

void MemoryCounterStore::confirmed(std::uint64_t counter) {
  std::lock_guard lock(mutex_);
  last_confirmed_ = std::max(last_confirmed_.value_or(0), counter);
}

std::uint64_t MemoryCounterStore::last_accepted() const {
  std::lock_guard lock(mutex_);
  return last_accepted_;
}

void MemoryCounterStore::accept(std::uint64_t counter) {
  std::lock_guard lock(mutex_);
  last_accepted_ = std::max(last_accepted_, counter);
}

void MemoryCounterStore::reanchor(std::uint64_t counter) {
  std::lock_guard lock(mutex_);
  last_accepted_ = counter;
}

}  // namespace dtmf::security
