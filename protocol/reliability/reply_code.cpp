#include "reliability/reply_code.h"

#include <string_view>

namespace dtmf::reliability {

namespace {

constexpr int kAddresses = 8;
constexpr int kSequences = 16;
constexpr int kRepliesPerAddress = kSequences + 1;  // ACK 0..15, then NACK
constexpr int kReplies = kAddresses * kRepliesPerAddress;
// Address 0's words come first (ACK 0..15, NACK); then every other address's ACKs, then
// their NACKs.
constexpr int kOtherAcks = kRepliesPerAddress;
constexpr int kOtherNacks = kOtherAcks + (kAddresses - 1) * kSequences;

// Each word's tones, band by band. The first 17 (ACK 0..15, then NACK, address 0) were found
// on 2026-11-25 by a seeded random search (std::mt19937 seeded 20261125, a word kept when it
// repeats no band's tone across its chords and differs from every word kept in at least 7
// tones). Addresses 1..7 (ACK 0..15 of each, then the seven NACKs) came on 2026-11-29 from
// the same rule applied to every word in counting order (band 0 the lowest digit): that
// search found only 113 words in 50 million random draws, counting order 138. A table, not
// the search: counting to the 136th word takes 0.6 s. reply_code_test checks every rule.
constexpr std::string_view kWords[kReplies] = {
    "310202133333", "031131310322", "130222023030", "120011311122", "202321020130", "333331212113", "312312120220",
    "103220231332", "220102102220", "231221112300", "113003232210", "002001120212", "031030223123", "001323122010",
    "213030330201", "320123012001", "012331133022", "111111000000", "022222100000", "303332010000", "233213320000",
    "210333101000", "000211211000", "123321331000", "132133213000", "331023200100", "102012330100", "113232221100",
    "223031002100", "010223332100", "323013111200", "330131021200", "033312202200", "001122313200", "212122031300",
    "301213033300", "020032233300", "222101310010", "332203001010", "320231132010", "121302203010", "123223010110",
    "200002011110", "030301323110", "013121101210", "231032322210", "222333033210", "012033300310", "311201220310",
    "100103321020", "021311230120", "212211303120", "101301012220", "133002000320", "203133130320", "210013022320",
    "002203113130", "323122230230", "200011133230", "132011221330", "123113302330", "221310110001", "003120220001",
    "032332321001", "311230202001", "130210001101", "312020121101", "203322132101", "322212213101", "111313323101",
    "100232312301", "232013103301", "112300020011", "301102130011", "233130011011", "330320103011", "021233313011",
    "023000201111", "100333231111", "111022002111", "032323210211", "120100333211", "203023321311", "010130122311",
    "012113201021", "231303302021", "123212032021", "313203100121", "322130000221", "003310311221", "330000212221",
    "101013210321", "222200131321", "211223030031", "300312222031", "033012110131", "321300032131", "213302001231",
    "102020013231", "033203222331", "200110332002", "001230130102", "232320313102", "110320222202", "321321003202",
    "322111130302", "213200322112", "310030033112", "231103113212", "130101202312", "021020332312", "302233220022",
    "333313021122", "313031201322", "120233003322", "003303330032", "223211101032", "311110123032", "231010000232",
    "110113031232", "121131232203", "202130123203", "030021301303", "202222333013", "232302100113", "020332111213",
    "302100211313", "331132003313", "313101022023", "230311013023", "112000301223", "221002313323", "131200210033",
    "022310303033", "220020112133", "001211322133",
};

int word_index(const NamedReply& reply) {
  const int address = reply.address % kAddresses;
  if (address == 0) return reply.ack ? reply.sequence % kSequences : kSequences;
  return reply.ack ? kOtherAcks + (address - 1) * kSequences + reply.sequence % kSequences
                   : kOtherNacks + (address - 1);
}

NamedReply reply_of(int index) {
  if (index < kOtherAcks) return {index < kSequences, static_cast<std::uint8_t>(index < kSequences ? index : 0), 0};
  if (index < kOtherNacks) {
    const int rest = index - kOtherAcks;
    return {true, static_cast<std::uint8_t>(rest % kSequences), static_cast<std::uint8_t>(1 + rest / kSequences)};
  }
  return {false, 0, static_cast<std::uint8_t>(1 + index - kOtherNacks)};
}

ReplyTones tones_of(std::string_view word) {
  ReplyTones t{};
  for (std::size_t i = 0; i < t.size(); ++i) t[i] = static_cast<std::uint8_t>(word[i] - '0');
  return t;
}

}  // namespace

ReplyTones reply_codeword(const NamedReply& reply) { return tones_of(kWords[word_index(reply)]); }

std::optional<NamedReply> read_reply(const ReplyReading& reading, int tones_needed) {
  for (int r = 0; r < kReplies; ++r) {
    const std::string_view word = kWords[r];
    int agree = 0;
    for (std::size_t t = 0; t < word.size(); ++t) agree += reading[t] == word[t] - '0' ? 1 : 0;
    if (agree >= tones_needed) return reply_of(r);
  }
  return std::nullopt;
}

}  // namespace dtmf::reliability
