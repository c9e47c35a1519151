// Reaches past the fixture library's public header on purpose: the check must refuse it.
#include "lib/api.hpp"
#include "lib/inner/detail.hpp"
