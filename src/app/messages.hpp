#pragma once
// The command's messages: what comes from outside (a file name, an element's id, an attribute's
// value) is printed with its control characters and malformed UTF-8 escaped (base::printable),
// so that no input can move the cursor, change the title or clear the terminal it is shown on.
#include <string>

namespace curvemesh::app {

// "curvemesh: " and the message, escaped, on one line of stderr.
void say(const std::string& message);

// What a run that ran out of memory says: the address-space limit it ran under, if any
// (--memory-limit, or the batch's), and the limits that refuse such drawings sooner.
std::string out_of_memory_message();

// A warning about the input: "curvemesh: INPUT: warning: MESSAGE".
void warn(const std::string& input, const std::string& message);

}  // namespace curvemesh::app
