#pragma once
// docs/configuration.md, generated from the option table (config/option_table.cc): every key with its type,
// default, unit, allowed values, whether it changes the points (the resume hash) and the fusion methods that read
// it. `sacfuse gen-docs configuration` prints it; tests/generated_docs_test.cc fails when the committed page differs.
#include <string>

namespace sacfuse {

std::string ConfigurationMarkdown();

}  // namespace sacfuse
