// How numbers are written into the CSV files of a run: 10 significant digits (num, shared with
// the messages that quote the same measurements).
#pragma once

#include "fairshape/core/message_format.h"
