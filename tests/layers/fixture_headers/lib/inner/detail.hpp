#pragma once
// Internal to the fixture library.
