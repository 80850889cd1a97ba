#!/usr/bin/env bash
# Prints a sacfuse YAML config with every relative path made absolute (relative to the config's own folder, as
# sacfuse reads them: input.path, input.cameras, fusion.superpixel_cache_dir, evaluation.reference,
# evaluation.mask) and output.dir replaced by OUT_DIR, so the copy can live anywhere. Used by the benchmarks that
# run one config into their own output folders (compare_colmap.sh; timed_run.sh for ab_time.sh, stage_ladder.sh).
#
#   tools/bench/config_with_output.sh CONFIG OUT_DIR [SECTION.KEY=VALUE...] > COPY.yaml
#
# Each SECTION.KEY=VALUE sets one option in the copy (VALUE read as YAML: false, 2, select), e.g.
# coregistration.enabled=false. Any YAML style (the flow-style sections `sacfuse simulate` writes, or block style);
# comments are not kept. Needs /usr/bin/python3 with PyYAML (Debian: python3-yaml, installed by
# tools/install_deps.sh). Exits 3 when the config is not a YAML mapping, 2 on a malformed SECTION.KEY=VALUE.
set -euo pipefail
[[ $# -ge 2 ]] || { sed -n '2,13p' "$0" >&2; exit 2; }
/usr/bin/python3 - "$@" <<'PY'
import os
import sys

import yaml

config_path, out_dir, overrides = sys.argv[1], sys.argv[2], sys.argv[3:]
base = os.path.dirname(os.path.abspath(config_path))
with open(config_path) as f:
    config = yaml.safe_load(f)
if not isinstance(config, dict):
    print(f"{config_path}: not a YAML mapping", file=sys.stderr)
    sys.exit(3)
PATH_KEYS = [("input", "path"), ("input", "cameras"), ("fusion", "superpixel_cache_dir"),
             ("evaluation", "reference"), ("evaluation", "mask")]
for section, key in PATH_KEYS:
    value = (config.get(section) or {}).get(key)
    if isinstance(value, str) and value and not os.path.isabs(value):
        config[section][key] = os.path.normpath(os.path.join(base, value))
config.setdefault("output", {})
if config["output"] is None:
    config["output"] = {}
config["output"]["dir"] = out_dir
for override in overrides:
    path, equals, value = override.partition("=")
    section, dot, key = path.partition(".")
    if not equals or not dot or not section or not key or "." in key:
        print(f"not SECTION.KEY=VALUE: {override!r}", file=sys.stderr)
        sys.exit(2)
    if not isinstance(config.get(section), dict):
        config[section] = {}
    config[section][key] = yaml.safe_load(value)
yaml.safe_dump(config, sys.stdout, default_flow_style=False, sort_keys=False)
PY
