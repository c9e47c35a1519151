#pragma once
// What a Range header asks of a file of known size (RFC 9110 §14): one range of bytes, the whole
// file, or nothing it holds. Only a single range is honoured; a list of ranges or a header that
// is not a bytes range is ignored (the whole file, 200), as the RFC allows. No sockets here, so
// the rules are tested on strings.
#include <cstdint>
#include <string_view>

namespace arena::ops {

struct byte_range {
    enum class kind { whole, partial, unsatisfiable };
    kind what = kind::whole;
    uint64_t first = 0;   // byte offset of the first byte sent
    uint64_t length = 0;  // bytes sent (the whole file's size for `whole`)
};

// header: the Range header's value ("" when absent); size: the file's size in bytes.
[[nodiscard]] byte_range parse_byte_range(std::string_view header, uint64_t size);

}  // namespace arena::ops
