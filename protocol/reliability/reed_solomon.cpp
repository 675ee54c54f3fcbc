#include "reliability/reed_solomon.h"

// libfec is C, and its header does not say so.
extern "C" {
#include <fec.h>
}

#include <algorithm>
#include <stdexcept>
#include <string>

namespace dtmf::reliability {

namespace {
// Primitive polynomials of GF(2^m), lowest coefficient in the lowest bit.
int primitive_polynomial(int symbol_bits) {
  switch (symbol_bits) {
    case 3:
      return 0xb;  // x^3 + x + 1
    case 4:
      return 0x13;  // x^4 + x + 1
    case 5:
      return 0x25;  // x^5 + x^2 + 1
    case 6:
      return 0x43;  // x^6 + x + 1
    case 7:
      return 0x89;  // x^7 + x^3 + 1
    case 8:
      return 0x11d;  // x^8 + x^4 + x^3 + x^2 + 1
    default:
      throw std::invalid_argument("Reed-Solomon symbols of " + std::to_string(symbol_bits) + " bits: use 3..8");
  }
}
}  // namespace

ReedSolomon::ReedSolomon(int symbol_bits, int n, int k) : n_(n), k_(k) {
  const int full = (1 << symbol_bits) - 1;
  if (k <= 0 || n <= k || n > full) {
    throw std::invalid_argument("RS(" + std::to_string(n) + ", " + std::to_string(k) + ") over GF(2^" +
                                std::to_string(symbol_bits) + ") is not a code");
  }
  // First consecutive root 1, primitive element 1; shortened by full - n leading zeros.
  rs_ = init_rs_char(symbol_bits, primitive_polynomial(symbol_bits), 1, 1, n - k, full - n);
  if (!rs_)
    throw std::runtime_error("libfec could not set up RS(" + std::to_string(n) + ", " + std::to_string(k) + ")");
}

ReedSolomon::~ReedSolomon() { free_rs_char(rs_); }

void ReedSolomon::encode(std::span<const std::uint8_t> data, std::span<std::uint8_t> word) const {
  if (static_cast<int>(data.size()) != k_ || static_cast<int>(word.size()) != n_) {
    throw std::invalid_argument("Reed-Solomon encode: wrong data or codeword length");
  }
  std::copy(data.begin(), data.end(), word.begin());
  encode_rs_char(rs_, word.data(), word.data() + k_);
}

std::vector<std::uint8_t> ReedSolomon::encode(std::span<const std::uint8_t> data) const {
  std::vector<std::uint8_t> word(static_cast<std::size_t>(n_));
  encode(data, word);
  return word;
}

std::optional<int> ReedSolomon::decode(std::span<const std::uint8_t> received, std::span<const int> erasures,
                                       std::span<std::uint8_t> data, int reserve) const {
  if (static_cast<int>(received.size()) != n_ || static_cast<int>(data.size()) != k_ ||
      static_cast<int>(erasures.size()) > parity() - reserve) {
    return std::nullopt;
  }
  std::uint8_t word[255];
  std::copy(received.begin(), received.end(), word);
  // libfec overwrites the positions array with the positions it corrected (up to n - k).
  int positions[255];
  std::copy(erasures.begin(), erasures.end(), positions);
  const int corrected = decode_rs_char(rs_, word, positions, static_cast<int>(erasures.size()));
  if (corrected < 0) return std::nullopt;
  int errors = 0;
  for (int i = 0; i < corrected; ++i) {
    if (std::find(erasures.begin(), erasures.end(), positions[i]) == erasures.end()) ++errors;
  }
  if (2 * errors + static_cast<int>(erasures.size()) > parity() - reserve) return std::nullopt;
  std::copy(word, word + k_, data.begin());
  return errors;
}

}  // namespace dtmf::reliability
