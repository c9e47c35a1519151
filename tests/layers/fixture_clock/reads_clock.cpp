// A file that breaks the rule on purpose: check_no_io must refuse it (layers_check_fails_on_clock).
#include <chrono>

long now() {
    return std::chrono::steady_clock::now().time_since_epoch().count();
}
