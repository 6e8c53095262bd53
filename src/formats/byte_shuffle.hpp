#pragma once
// HDF5's shuffle filter for 8-byte elements: byte k of every element together (plane k), and back. Sixteen
// elements at a time with SSE2 where the machine has it: the 16 × 8 byte block is transposed by four rounds
// of byte interleaving (each round rotates the bits of a byte's index in the block by one place; four turn
// element-major into plane-major), three rounds undo it. A byte at a time elsewhere, and for the rows past
// the last whole block.
#include <cstddef>
#include <cstdint>

namespace pkm::formats {

/// `count` elements of 8 bytes from `elements` into 8 planes of `count` bytes at `planes`.
void shuffle_bytes8(const std::uint8_t* elements, std::size_t count, std::uint8_t* planes);

/// The first `rows` elements back from 8 planes of `plane_bytes` bytes each (rows ≤ plane_bytes) into
/// `elements` (8 · rows bytes).
void unshuffle_bytes8(const std::uint8_t* planes, std::size_t plane_bytes, std::size_t rows,
                      std::uint8_t* elements);

}  // namespace pkm::formats
