// A file that breaks the rule on purpose: check_no_io must refuse it (layers_check_fails_on_asio).
#pragma once
#include <boost/asio.hpp>
