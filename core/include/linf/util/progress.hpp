// How far a long core call has come, for whoever watches it: the editor's progress bar, the
// batch's lines on stderr. A call names its stages ("building the diagram") and, inside a
// stage, how many of its parts are done of how many. It is told at each stage's start (done 0)
// and then at most every tenth of a second, one call at a time, from whichever of the core's
// threads ended a part: it must be quick and must not throw. Empty: nobody is told.
#pragma once
#include <cstddef>
#include <functional>

namespace linf {

using ProgressFn = std::function<void(const char* stage, std::size_t done, std::size_t total)>;

}  // namespace linf
