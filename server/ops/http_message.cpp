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

std::string format_post(std::string_view host, uint16_t port, std::string_view path, std::string_view json_body) {
    std::string out;
    out.append("POST ")
        .append(path)
        .append(" HTTP/1.1\r\nHost: ")
        .append(host)
        .append(":")
        .append(std::to_string(port));
    out.append("\r\nContent-Type: application/json\r\nContent-Length: ").append(std::to_string(json_body.size()));
    out.append("\r\nConnection: close\r\n\r\n").append(json_body);
    return out;
}

}  // namespace arena::ops
