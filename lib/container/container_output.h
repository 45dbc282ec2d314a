// The one output of the tools that read a container (or a mesh) and write it back with their
// chunks added (limn-classify, limn-tables, limn-seams, limn-blend): the container file and its
// --depfile, opened before any work so that a refused terminal or an unwritable folder fails
// first, and committed together, so that a failed run leaves neither behind.
#pragma once

#include "base/io.h"
#include "container/container.h"

#include <string>
#include <vector>

namespace limn {

class ContainerOutput {
public:
    // Refuses an output that names the input (unless the input is a container, which these tools
    // may update in place), then opens the output and the depfile (empty: none).
    ContainerOutput(const std::string& output, const std::string& depfile, const std::string& input);

    // Writes `container`, then the depfile's rule (the output from `inputs`); a depfile that
    // cannot be written fails the run before the output lands. Then commits both.
    void commit(const Container& container, const std::vector<std::string>& inputs);

private:
    std::string output_;
    OutputFile out_;
    Depfile depfile_;
};

} // namespace limn
