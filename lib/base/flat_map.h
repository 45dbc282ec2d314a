// A hash map from 64-bit keys to 32-bit values for the hot lookups of topology building (the
// view-adaptive edge pieces look up every lattice point along every element side: millions on a
// 100k-face mesh). Open addressing with linear probing in one flat array, sized once from the
// expected count, so a lookup touches one or two cache lines instead of std::unordered_map's
// node chain. Insertion only; iteration order is never used, so results do not depend on it.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <utility>
#include <vector>

namespace limn {

class FlatKeyMap {
  public:
    static constexpr uint32_t kAbsent = 0xFFFFFFFFu; // the one value that cannot be stored

    // Room for `expected` keys at a load of at most one half; grows by rehashing beyond that.
    explicit FlatKeyMap(size_t expected = 16) { rehash(std::bit_ceil(std::max<size_t>(16, 2 * expected))); }

    // The value of `key`, or kAbsent.
    uint32_t find(uint64_t key) const {
        for (size_t i = slot(key);; i = (i + 1) & mask_) {
            const Slot& s = slots_[i];
            if (s.value == kAbsent) return kAbsent;
            if (s.key == key) return s.value;
        }
    }

    // Inserts key -> value unless the key is there; returns the stored value and whether it
    // was inserted (like try_emplace).
    std::pair<uint32_t, bool> tryEmplace(uint64_t key, uint32_t value) {
        if (2 * (size_ + 1) > slots_.size()) rehash(2 * slots_.size());
        for (size_t i = slot(key);; i = (i + 1) & mask_) {
            Slot& s = slots_[i];
            if (s.value == kAbsent) {
                s = {key, value}, ++size_;
                return {value, true};
            }
            if (s.key == key) return {s.value, false};
        }
    }

    size_t size() const { return size_; }

  private:
    size_t slot(uint64_t key) const {
        // Fibonacci hashing: the multiply spreads nearby keys (lattice neighbours) apart.
        return static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
    }
    void rehash(size_t capacity) {
        std::vector<Slot> old = std::move(slots_);
        slots_.assign(capacity, Slot{});
        mask_ = capacity - 1;
        shift_ = 64 - std::countr_zero(capacity);
        size_ = 0;
        for (const Slot& s : old)
            if (s.value != kAbsent) tryEmplace(s.key, s.value);
    }

    // Key and value side by side: a probe reads one cache line.
    struct Slot {
        uint64_t key = 0;
        uint32_t value = kAbsent;
    };
    std::vector<Slot> slots_;
    size_t mask_ = 0, size_ = 0;
    int shift_ = 64;
};

} // namespace limn
