#pragma once
// What arena-healthcheck reads of a response, as a pure function over text.
#include <string_view>

namespace arena::ops {

// The status code of "HTTP/1.x NNN ...", or 0 when the text does not start like that.
int parse_response_status(std::string_view response);

}  // namespace arena::ops
