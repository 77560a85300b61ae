// A first-in first-out queue in one ring of slots that doubles when full.
// The planner's queues take and drop an element per block: std::deque
// allocates a chunk every few elements of that size and indexes in two
// levels; here the slots are reused and an index is a mask. Internal to the
// plan module.
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

namespace vcpost::plan::detail {

// T must be default-constructible and movable. Indices count from the
// front; references stay valid until the next element is added.
template <class T>
class RingQueue {
 public:
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }

  T& operator[](std::size_t i) { return slots_[(head_ + i) & mask_]; }
  const T& operator[](std::size_t i) const { return slots_[(head_ + i) & mask_]; }
  T& front() { return (*this)[0]; }
  const T& front() const { return (*this)[0]; }
  T& back() { return (*this)[size_ - 1]; }
  const T& back() const { return (*this)[size_ - 1]; }

  void push_back(T value) { emplace_back() = std::move(value); }
  // Appends a default-constructed element to fill in place (a struct built
  // aside and copied in costs more than its fields).
  T& emplace_back() {
    if (size_ == slots_.size()) grow();
    T* slot = &slots_[(head_ + size_) & mask_];
    std::destroy_at(slot);
    // Default- (not value-) initialised: T's member initialisers, without
    // zeroing the whole slot first.
    std::uninitialized_default_construct_n(slot, 1);
    ++size_;
    return *slot;
  }
  // Drops the first n elements (n <= size()).
  void pop_front(std::size_t n = 1) {
    head_ = (head_ + n) & mask_;
    size_ -= n;
  }
  void pop_back() { --size_; }
  void clear() {
    head_ = 0;
    size_ = 0;
  }

 private:
  void grow() {
    std::vector<T> bigger(std::max<std::size_t>(16, 2 * slots_.size()));
    for (std::size_t i = 0; i < size_; ++i) bigger[i] = std::move((*this)[i]);
    slots_.swap(bigger);
    head_ = 0;
    mask_ = slots_.size() - 1;
  }

  std::vector<T> slots_;  // a power of two of them (or none)
  std::size_t head_ = 0;  // slot of the front
  std::size_t size_ = 0;
  std::size_t mask_ = 0;  // slots_.size() - 1
};

}  // namespace vcpost::plan::detail
