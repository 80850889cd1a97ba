#pragma once
// The one table of the options of `sacfuse run` (config/option_table.cc): every YAML key once, bound to its
// field (whose initialiser is the default), with its type, unit, range or choices, doc, whether it changes the
// points (ResultSettingsText, the resume hash) and the fusion methods that read it (only the keys of the method in
// use are range-checked). Parsing, validation, --print-defaults and the resume hash all read it.
#include <cstdint>
#include <vector>

#include "config/config_schema.h"
#include "config/job_config.h"

namespace sacfuse {

// The scope bit of a method (OptionSpec::scopes): a key read by several methods has the OR of their bits.
constexpr uint32_t MethodScope(FusionMethodKind kind) { return 1u << static_cast<unsigned>(kind); }
// The table bound to `config`'s fields; it must not outlive `config`.
ConfigSchema MakeOptionTable(JobConfig* config);
// Every row with the values of `config` (JobConfig{}: the defaults), in table order.
std::vector<OptionRow> JobOptionRows(const JobConfig& config);

}  // namespace sacfuse
