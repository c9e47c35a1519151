#include "server/ops/http_message.hpp"

namespace arena::ops {

int parse_response_status(std::string_view response) {
    if (response.size() < 12 || response.substr(0, 7) != "HTTP/1." || response[8] != ' ') return 0;
    int status = 0;
    for (size_t i = 9; i < 12; ++i) {
        if (response[i] < '0' || response[i] > '9') return 0;
        status = status * 10 + (response[i] - '0');
    }
    return status;
}

}  // namespace arena::ops
