#pragma once
// The fixture library's public header.
