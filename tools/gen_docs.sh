#!/usr/bin/env bash
# Regenerates the committed reference pages from the built binary: docs/configuration.md (the option table) and
# docs/cli.md (every command's --help). tests/generated_docs_test.cc fails while they differ from what the binary
# prints, so run this after changing an option, a flag or a help text, and commit the pages.
#
#   tools/gen_docs.sh        SACFUSE: the binary (default build/bin/sacfuse of this checkout)
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${SACFUSE:-build/bin/sacfuse}
[[ -x $bin ]] || { echo "$0: $bin not found; build it (tools/build.sh --target sacfuse) or set SACFUSE" >&2; exit 2; }
mkdir -p docs
"$bin" gen-docs configuration --out docs/configuration.md
"$bin" gen-docs cli --out docs/cli.md
echo "wrote docs/configuration.md and docs/cli.md with $("$bin" --version)"
