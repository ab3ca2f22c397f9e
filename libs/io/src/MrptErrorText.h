/* Internal: the one-line text of an exception (common::oneLineError) under
 * the name the io sources use. */
#pragma once

#include <roislam/common/ErrorText.h>

namespace roislam::io::detail
{
using common::oneLineError;
}  // namespace roislam::io::detail
