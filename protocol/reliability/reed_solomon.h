// Reliability layer: a shortened Reed–Solomon code over GF(2^m), through Phil Karn's libfec
// (Debian's libfec-dev), with errors-and-erasures decoding.
//
// The fast profile sends one m-bit symbol per tone, so one RS symbol is one tone: a tone lost
// to a fade or drowned by a whine is an erasure the code fills in, a tone read wrong is an
// error it corrects. Decoding also tells how many symbols it changed that were not marked as
// erasures (errors), so a caller can keep part of the code's redundancy for detection
// (2 * errors + erasures <= parity symbols - reserve): a code pushed to its limit "corrects"
// noise into some codeword, and then only the CRC stands between noise and a wrong accept.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace dtmf::reliability {

class ReedSolomon {
 public:
  // RS(n, k) over GF(2^symbol_bits), n <= 2^symbol_bits - 1. Throws std::invalid_argument.
  ReedSolomon(int symbol_bits, int n, int k);
  ~ReedSolomon();
  ReedSolomon(const ReedSolomon&) = delete;
  ReedSolomon& operator=(const ReedSolomon&) = delete;

  int n() const { return n_; }
  int k() const { return k_; }
  int parity() const { return n_ - k_; }

  // Writes the codeword of `data` (k symbols) to `word` (n symbols): the data, then the
  // n - k parity symbols. Allocates nothing (it runs in the robot's receive path).
  void encode(std::span<const std::uint8_t> data, std::span<std::uint8_t> word) const;
  std::vector<std::uint8_t> encode(std::span<const std::uint8_t> data) const;

  // Writes the data of the codeword nearest `received` (n symbols), given the erased
  // positions, to `data` (k symbols) and returns the symbols it changed outside the
  // erasures (errors); nothing when 2 * errors + erasures would exceed parity() - reserve,
  // or decoding fails. Allocates nothing.
  std::optional<int> decode(std::span<const std::uint8_t> received, std::span<const int> erasures,
                            std::span<std::uint8_t> data, int reserve = 0) const;

 private:
  int n_, k_;
  void* rs_;
};

}  // namespace dtmf::reliability
