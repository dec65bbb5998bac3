#!/usr/bin/env bash
# The layers as a test (docs/ARCHITECTURE.md, "Layers"): each layer may include only itself and the
# layers before it,
#     math -> mass -> dynamics -> forces -> integrate -> sim -> io -> study -> robot -> fit
# (include/tumble/*.hpp at the top level, e.g. error.hpp, belongs to math). It fails, naming file:line
# and the include, when
#   - a header (include/tumble/<layer>/) or source (src/<layer>/) includes "tumble/<higher layer>/...";
#   - anything includes "tumble/<folder>/..." for a folder that is not a layer;
#   - a public header (include/) includes a file from src/;
#   - a source of one layer includes a private header of another by a relative path ("../mass/x.hpp");
#   - a test includes a file from src/ by a relative path ("../../src/..."): tests include a layer's
#     private header as "<layer>/name.hpp" (src/ is on tumble_tests' include path);
#   - src/ or include/tumble/ has a folder that is not a layer, a source sits directly in src/, or the
#     order in src/CMakeLists.txt (TUMBLE_LAYERS) differs from the one here.
#
#   tests/lint/check_layers.sh [ROOT]     lint the tree at ROOT (default: this checkout)
#   tests/lint/check_layers.sh --self-test
#                                         build scratch trees with one violation each and check that
#                                         every one is reported (and that a clean tree passes)
# Exit status: 0 clean, 1 violations found (or a self-test case failed), 2 usage error.
set -euo pipefail

LAYERS=(math mass dynamics forces integrate sim io study robot fit)

declare -A LAYER_INDEX=()
for i in "${!LAYERS[@]}"; do LAYER_INDEX[${LAYERS[i]}]=$i; done

layer_index() {  # layer_index NAME VAR: sets VAR to NAME's position in LAYERS, or -1
  if [[ -n "$1" && -n "${LAYER_INDEX[$1]+set}" ]]; then
    printf -v "$2" '%s' "${LAYER_INDEX[$1]}"
  else
    printf -v "$2" '%s' -1
  fi
}

normalize() {  # normalize PATH VAR: sets VAR to PATH (relative to the root) without "." and ".."
  local -a parts=() out=()
  local part
  IFS=/ read -r -a parts <<<"$1"
  for part in "${parts[@]}"; do
    case "$part" in
      "" | .) ;;
      ..) if [[ ${#out[@]} -gt 0 && "${out[-1]}" != .. ]]; then unset 'out[-1]'; else out+=(..); fi ;;
      *) out+=("$part") ;;
    esac
  done
  local IFS=/
  printf -v "$2" '%s' "${out[*]}"
}

order_text() {
  local IFS=' '
  local text="${LAYERS[*]}"
  echo "${text// / -> }"
}

lint() {
  local root="$1"
  local errors=0
  report() {  # report WHERE MESSAGE
    echo "$1: $2"
    errors=$((errors + 1))
  }

  # Folders and the order in CMake.
  local dir name index
  for dir in "$root"/src/*/ "$root"/include/tumble/*/; do
    [[ -d "$dir" ]] || continue
    name="$(basename "$dir")"
    layer_index "$name" index
    if [[ "$index" -lt 0 ]]; then
      report "${dir#"$root"/}" "folder '$name' is not a layer ($(order_text)); place it in the order in \
tests/lint/check_layers.sh and src/CMakeLists.txt (TUMBLE_LAYERS)"
    fi
  done
  local file
  for file in "$root"/src/*.cpp "$root"/src/*.hpp; do
    [[ -e "$file" ]] || continue
    report "${file#"$root"/}" "a source outside the layer folders src/<layer>/ (it is not built)"
  done
  if [[ -f "$root/src/CMakeLists.txt" ]]; then
    local line cmake_layers
    line="$(grep -n '^[[:space:]]*set(TUMBLE_LAYERS ' "$root/src/CMakeLists.txt" | head -1 || true)"
    cmake_layers="$(sed -E 's/^[0-9]+:[[:space:]]*set\(TUMBLE_LAYERS[[:space:]]+([^)]*)\).*/\1/' <<<"$line" \
                    | tr -s ' ')"
    if [[ -z "$line" ]]; then
      report "src/CMakeLists.txt" "no 'set(TUMBLE_LAYERS ...)' line to compare with the order $(order_text)"
    elif [[ "$cmake_layers" != "${LAYERS[*]}" ]]; then
      report "src/CMakeLists.txt:${line%%:*}" "TUMBLE_LAYERS is '$cmake_layers' but the lint's order is \
'${LAYERS[*]}' (tests/lint/check_layers.sh)"
    fi
  fi

  # Every #include line of every C++ file under include/, src/ and tests/ (one grep: "file:line:text").
  local rel own own_index hit lineno text path target target_index resolved
  while IFS= read -r hit; do
    rel="${hit%%:*}"
    hit="${hit#*:}"
    lineno="${hit%%:*}"
    text="${hit#*:}"
    case "$rel" in
      include/tumble/*/*) own="${rel#include/tumble/}"; own="${own%%/*}" ;;
      include/tumble/*) own="${LAYERS[0]}" ;;
      src/*/*) own="${rel#src/}"; own="${own%%/*}" ;;
      *) own="" ;;
    esac
    layer_index "$own" own_index
    [[ "$text" =~ ^[[:space:]]*(#[[:space:]]*include[[:space:]]*[\<\"]([^\>\"]*)[\>\"]) ]] || continue
    text="${BASH_REMATCH[1]}"  # the directive, without indentation or a trailing comment
    path="${BASH_REMATCH[2]}"

    # tumble/<layer>/...: the layer must exist and, in the library, not be above this file's.
    if [[ "$path" =~ ^tumble/([^/]+)/ ]]; then
      target="${BASH_REMATCH[1]}"
      layer_index "$target" target_index
      if [[ "$target_index" -lt 0 ]]; then
        report "$rel:$lineno" "$text: '$target' is not a layer ($(order_text))"
      elif [[ "$own_index" -ge 0 && "$target_index" -gt "$own_index" ]]; then
        report "$rel:$lineno" "$text: layer '$own' includes layer '$target' above it ($(order_text))"
      fi
    fi

    # Paths into src/: literal, or relative ones that resolve there.
    resolved=""
    if [[ "$text" == *'"'* && "$path" == *..* ]]; then
      normalize "${rel%/*}/$path" resolved
    fi
    case "$rel" in
      include/*)
        if [[ "$path" =~ (^|/)src/ || "$resolved" == src/* ]]; then
          report "$rel:$lineno" "$text: a public header includes a private file from src/"
        fi
        ;;
      src/*)
        if [[ "$resolved" == src/* && "$resolved" != "src/$own/"* ]]; then
          target="${resolved#src/}"
          report "$rel:$lineno" "$text: layer '$own' includes a private header of src/${target%%/*}/ \
(make it public in include/tumble/ or move it)"
        fi
        ;;
      *)
        if [[ "$resolved" == src/* ]]; then
          report "$rel:$lineno" "$text: a test reaches into src/ by a relative path; include it as \
\"${resolved#src/}\" (src/ is on tumble_tests' include path)"
        fi
        ;;
    esac
  done < <(cd "$root" && find include src tests -type f \
             \( -name '*.hpp' -o -name '*.h' -o -name '*.cpp' -o -name '*.cc' -o -name '*.inl' \
                -o -name '*.ipp' -o -name '*.tpp' \) -print0 2>/dev/null | sort -z \
           | xargs -0 -r grep -nHE '^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"][^>"]+[>"]' || true)

  if [[ "$errors" -gt 0 ]]; then
    echo "check_layers: $errors violation(s) of the layer order $(order_text) (docs/ARCHITECTURE.md)"
    return 1
  fi
  echo "check_layers: no include breaks the layer order $(order_text)"
}

# --- self-test: a clean scratch tree passes; each broken variant fails and names file:line ----------
self_test() {
  local self scratch failures=0
  self="$(realpath "${BASH_SOURCE[0]}")"
  scratch="$(mktemp -d)"
  trap 'rm -rf "$scratch"' RETURN

  make_clean_tree() {  # make_clean_tree DIR
    local t="$1"
    rm -rf "$t"
    mkdir -p "$t"/include/tumble/{math,mass,sim} "$t"/src/{mass,sim} "$t"/tests/{mass,support}
    printf '#pragma once\n' >"$t/include/tumble/error.hpp"
    printf '#pragma once\n#include "tumble/error.hpp"\n#include <Eigen/Core>\n' >"$t/include/tumble/math/types.hpp"
    printf '#pragma once\n#include "tumble/math/types.hpp"\n' >"$t/include/tumble/mass/shapes.hpp"
    printf '#pragma once\n#include "tumble/mass/shapes.hpp"\n' >"$t/include/tumble/sim/simulate.hpp"
    printf '#pragma once\n' >"$t/src/mass/quadrature.hpp"
    printf '#include "tumble/mass/shapes.hpp"\n#include "quadrature.hpp"\n// #include "tumble/sim/simulate.hpp"\n' \
      >"$t/src/mass/shapes.cpp"
    printf '#include "tumble/sim/simulate.hpp"\n#include <tumble/mass/shapes.hpp>\n' >"$t/src/sim/simulate.cpp"
    printf '#pragma once\n' >"$t/tests/support/random.hpp"
    printf '#include "../support/random.hpp"\n#include "mass/quadrature.hpp"\n#include "tumble/sim/simulate.hpp"\n' \
      >"$t/tests/mass/shapes_test.cpp"
    printf 'set(TUMBLE_LAYERS %s)\n' "${LAYERS[*]}" >"$t/src/CMakeLists.txt"
  }

  # expect NAME EXPECTED-OUTPUT-SUBSTRING: run the lint on $scratch/tree, which must fail with it.
  expect() {
    local name="$1" want="$2" out status=0
    out="$(bash "$self" "$scratch/tree" 2>&1)" || status=$?
    if [[ "$status" -eq 1 && "$out" == *"$want"* ]]; then
      echo "self-test ok:   $name"
    else
      echo "self-test FAIL: $name (status $status, wanted output containing: $want)"
      echo "$out" | sed 's/^/    /'
      failures=$((failures + 1))
    fi
  }

  local t="$scratch/tree" out
  make_clean_tree "$t"
  if out="$(bash "$self" "$t" 2>&1)"; then
    echo "self-test ok:   a clean tree passes"
  else
    echo "self-test FAIL: a clean tree is reported"
    echo "$out" | sed 's/^/    /'
    failures=$((failures + 1))
  fi

  make_clean_tree "$t"
  printf '#pragma once\n#include "tumble/sim/simulate.hpp"\n' >"$t/include/tumble/mass/bad.hpp"
  expect "a header includes a higher layer" \
    "include/tumble/mass/bad.hpp:2: #include \"tumble/sim/simulate.hpp\": layer 'mass' includes layer 'sim' above it"

  make_clean_tree "$t"
  printf '// a comment\n\n#  include <tumble/io/scene.hpp>  // why not\n' >"$t/src/mass/bad.cpp"
  expect "a source includes a higher layer (angle brackets, spaces)" \
    "src/mass/bad.cpp:3: #  include <tumble/io/scene.hpp>: layer 'mass' includes layer 'io' above it"

  make_clean_tree "$t"
  printf '#pragma once\n#include "tumble/mass/shapes.hpp"\n' >"$t/include/tumble/bad.hpp"
  expect "a top-level header (the math layer) includes a higher layer" \
    "include/tumble/bad.hpp:2: #include \"tumble/mass/shapes.hpp\": layer 'math' includes layer 'mass'"

  make_clean_tree "$t"
  printf '#include "tumble/physics/x.hpp"\n' >"$t/src/mass/bad.cpp"
  expect "an include of a folder that is not a layer" \
    "src/mass/bad.cpp:1: #include \"tumble/physics/x.hpp\": 'physics' is not a layer"

  make_clean_tree "$t"
  printf '#pragma once\n#include "../../../src/mass/quadrature.hpp"\n' >"$t/include/tumble/mass/bad.hpp"
  expect "a public header includes src/ by a relative path" \
    "include/tumble/mass/bad.hpp:2: #include \"../../../src/mass/quadrature.hpp\": a public header includes a private file from src/"

  make_clean_tree "$t"
  printf '#pragma once\n#include "src/mass/quadrature.hpp"\n' >"$t/include/tumble/mass/bad.hpp"
  expect "a public header includes src/ by name" \
    "include/tumble/mass/bad.hpp:2: #include \"src/mass/quadrature.hpp\": a public header includes a private file from src/"

  make_clean_tree "$t"
  printf '#include "../mass/quadrature.hpp"\n' >"$t/src/sim/bad.cpp"
  expect "a source includes another layer's private header" \
    "src/sim/bad.cpp:1: #include \"../mass/quadrature.hpp\": layer 'sim' includes a private header of src/mass/"

  make_clean_tree "$t"
  printf '#include <gtest/gtest.h>\n#include "../../src/mass/quadrature.hpp"\n' >"$t/tests/mass/bad_test.cpp"
  expect "a test includes ../../src" \
    "tests/mass/bad_test.cpp:2: #include \"../../src/mass/quadrature.hpp\": a test reaches into src/ by a relative path; include it as \"mass/quadrature.hpp\""

  make_clean_tree "$t"
  mkdir -p "$t/src/physics"
  printf '#include "tumble/math/types.hpp"\n' >"$t/src/physics/x.cpp"
  expect "a src/ folder that is not a layer" "src/physics/: folder 'physics' is not a layer"

  make_clean_tree "$t"
  printf '#include "tumble/math/types.hpp"\n' >"$t/src/loose.cpp"
  expect "a source directly in src/" "src/loose.cpp: a source outside the layer folders"

  make_clean_tree "$t"
  printf '# layers\nset(TUMBLE_LAYERS math dynamics mass forces integrate sim io)\n' >"$t/src/CMakeLists.txt"
  expect "CMake's layer order differs" \
    "src/CMakeLists.txt:2: TUMBLE_LAYERS is 'math dynamics mass forces integrate sim io'"

  if [[ "$failures" -gt 0 ]]; then
    echo "check_layers self-test: $failures case(s) failed"
    return 1
  fi
  echo "check_layers self-test: every case passed"
}

case "${1:-}" in
  --self-test) self_test ;;
  -h | --help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' ;;
  -*) echo "usage: $0 [ROOT] | --self-test" >&2; exit 2 ;;
  *) lint "$(realpath "${1:-"$(dirname "${BASH_SOURCE[0]}")/../.."}")" ;;
esac
