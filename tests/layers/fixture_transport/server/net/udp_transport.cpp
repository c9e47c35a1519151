// A UDP transport that reaches into TCP's session: check_transports.cmake must refuse it.
#include "server/net/session.hpp"
