#include "server/rules/params_reader.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

namespace arena::rules {

namespace {

using nlohmann::json;

// Thrown by the reader at the first bad field; read_params_problem turns it into its line.
struct bad_param {
    std::string message;
};

std::string field(const std::string& name) {
    return "rules_params." + name;
}

// A bound as a person writes it: 1e4 as "10000", 0.5 as "0.5".
std::string text(double d) {
    std::string s = std::to_string(d);
    s.erase(s.find_last_not_of('0') + 1);
    if (s.back() == '.') s.pop_back();
    return s;
}

}  // namespace

const json* params_reader::find(const std::string& name) {
    seen_.insert(name);
    const auto it = object_.find(name);
    return it == object_.end() ? nullptr : &*it;
}

void params_reader::number(const char* name, world::real& out, double lo, double hi, bool lo_open) {
    const json* v = find(name);
    if (!v) return;
    const double d = v->is_number() ? v->get<double>() : NAN;
    if (!std::isfinite(d) || d < lo || (lo_open && d == lo) || d > hi)
        throw bad_param{field(name) + " must be a number in " + (lo_open ? "(" : "[") + text(lo) + ", " + text(hi) +
                        "]"};
    out = static_cast<world::real>(d);
}

void params_reader::whole(const char* name, uint32_t& out, uint64_t lo, uint64_t hi) {
    const json* v = find(name);
    if (!v) return;
    if (!v->is_number_unsigned() || v->get<uint64_t>() < lo || v->get<uint64_t>() > hi)
        throw bad_param{field(name) + " must be a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                        "]"};
    out = v->get<uint32_t>();
}

void params_reader::finish() const {
    for (const auto& [key, value] : object_.items())
        if (!seen_.count(key)) throw bad_param{"unknown field " + field(key)};
}

std::string read_params_problem(std::string_view rules_params, const std::function<void(params_reader&)>& fields) {
    try {
        const json object = rules_params.empty() ? json::object() : json::parse(rules_params);
        if (!object.is_object()) return "rules_params must be an object";
        params_reader reader(object);
        fields(reader);
        reader.finish();
    } catch (const bad_param& e) {
        return e.message;
    } catch (const json::exception& e) {
        return std::string("rules_params: invalid JSON: ") + e.what();
    }
    return "";
}

}  // namespace arena::rules
