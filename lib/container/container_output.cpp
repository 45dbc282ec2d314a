#include "container/container_output.h"

namespace limn {

namespace {

const std::string& refusingOverwrite(const std::string& output, const std::string& input) {
    refuseOverwritingInputs(output, {input}, isContainerFile);
    return output;
}

} // namespace

ContainerOutput::ContainerOutput(const std::string& output, const std::string& depfile, const std::string& input)
    : output_(refusingOverwrite(output, input)), out_(output, OutputFile::Kind::Binary),
      depfile_(depfile, {output}, {input}) {}

void ContainerOutput::commit(const Container& container, const std::vector<std::string>& inputs) {
    out_.write(serializeContainer(container));
    depfile_.setRule(output_, inputs);
    depfile_.prepare(); // a depfile that cannot be written fails the run before the output lands
    out_.commit();
    depfile_.commit();
}

} // namespace limn
