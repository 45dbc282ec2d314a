// A support's vertices and their indices in it, while the support is gathered: a small
// open-addressing table on the stack (Fibonacci hashing, at most half full). Supports are
// gathered for every irregular face and every corner tried (hundreds of thousands on a scanned
// mesh), where a search or an allocation per vertex showed in limn-tables' profile.
#pragma once

#include "topology/topology.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <utility>

namespace limn {

class SupportIndex {
public:
    static constexpr size_t kMaxVertices = 512;

    // For at most `capacity` (<= kMaxVertices) vertices.
    explicit SupportIndex(size_t capacity) {
        if (capacity > kMaxVertices) throw std::logic_error("SupportIndex: more vertices than it holds");
        while (slots_ < 2 * capacity) slots_ *= 2;
        bits_ = std::countr_zero(slots_);
        std::fill_n(vertex_.begin(), slots_, kNone);
    }

    // v's index, and whether v was new (then its index is `next`).
    std::pair<uint32_t, bool> insert(uint32_t v, uint32_t next) {
        for (size_t i = (v * 0x9E3779B1u) >> (32 - bits_);; i = (i + 1) & (slots_ - 1)) {
            if (vertex_[i] == v) return {index_[i], false};
            if (vertex_[i] == kNone) {
                vertex_[i] = v;
                index_[i] = next;
                return {next, true};
            }
        }
    }

private:
    size_t slots_ = 16;
    int bits_ = 4;
    std::array<uint32_t, 2 * kMaxVertices> vertex_, index_;
};

} // namespace limn
