#!/usr/bin/env bash
# Print the path of the rodcontact program the tools run: $RODCONTACT when it is set; else,
# in an installation (this file in PREFIX/share/rodcontact/scripts/lib/, put there by
# `cmake --install`), PREFIX/bin/rodcontact; else, in a source tree (this file in
# <repo>/scripts/lib/), <repo>/build/rodcontact, the build scripts/setup.sh makes.
# The path may not exist yet: the caller checks it and says so.
#
#   exe=$(scripts/lib/find_rodcontact.sh)

set -uo pipefail

if [[ -n ${RODCONTACT:-} ]]; then
    echo "$RODCONTACT"
    exit 0
fi
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
if [[ $root == */share/rodcontact ]]; then
    echo "${root%/share/rodcontact}/bin/rodcontact"
else
    echo "$root/build/rodcontact"
fi
