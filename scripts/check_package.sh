#!/usr/bin/env bash
# Checks what scripts/package.sh made, as a user of the package meets it (issue 81; run by
# .ci/run, as root on a machine without rattleback installed):
#
#   scripts/check_package.sh DEB ARCHIVE
#
# The archive's listing is checked; the package is installed with dpkg -i, then `man -w
# rattleback`, `rattleback presets` from PATH, and a completion in bash, zsh and fish (each where
# installed) through the installed files, none of them naming the build's path; then it is
# removed, and nothing of it is left.
set -euo pipefail
if [ $# -ne 2 ]; then
  echo "usage: $0 DEB ARCHIVE" >&2
  exit 2
fi
deb=$1
archive=$2
fail() {
  echo "check_package: $*" >&2
  exit 1
}

listing=$(tar -tzf "$archive")
top=$(printf '%s\n' "$listing" | head -n 1 | cut -d/ -f1)
for f in rattleback doc/rattleback.1 complete/rattleback.bash complete/_rattleback \
  complete/rattleback.fish README.md CHANGELOG.md LICENSE-MIT LICENSE-APACHE; do
  printf '%s\n' "$listing" | grep -qx "$top/$f" || fail "the archive lacks $top/$f"
done
echo "check_package: the archive holds the binary, its manual, completions, README, licences"

if command -v rattleback > /dev/null; then
  fail "rattleback is already installed here ($(command -v rattleback)): the check needs a clean machine"
fi
dpkg -i "$deb" > /dev/null
trap 'dpkg -r rattleback > /dev/null 2>&1 || true' EXIT
[ "$(command -v rattleback)" = /usr/bin/rattleback ] || fail "rattleback is not on PATH"
for f in /usr/share/man/man1/rattleback.1.gz /usr/share/bash-completion/completions/rattleback \
  /usr/share/zsh/vendor-completions/_rattleback \
  /usr/share/fish/vendor_completions.d/rattleback.fish /usr/share/doc/rattleback/copyright; do
  [ -f "$f" ] || fail "the package did not install $f"
done
if command -v man > /dev/null; then
  [ "$(man -w rattleback)" = /usr/share/man/man1/rattleback.1.gz ] || fail "man -w rattleback"
  man rattleback 2> /dev/null | grep -q "EXIT STATUS" || fail "man rattleback does not read"
  echo "check_package: man -w rattleback is $(man -w rattleback)"
else
  echo "check_package: warning: man is not installed: man -w not checked"
fi
cd /tmp
rattleback presets | grep -q subcritical || fail "rattleback presets"
echo "check_package: rattleback presets lists the shipped presets"
if grep -rq "target/release" /usr/share/bash-completion/completions/rattleback \
  /usr/share/zsh/vendor-completions/_rattleback \
  /usr/share/fish/vendor_completions.d/rattleback.fish; then
  fail "an installed completion names the build's path"
fi

# bash: the installed file, a completion of `--preset kap`.
got=$(bash -c 'source /usr/share/bash-completion/completions/rattleback
  COMP_WORDS=(rattleback --preset kap); COMP_CWORD=2; COMP_TYPE=9
  _clap_complete_rattleback rattleback kap --preset; printf "%s\n" "${COMPREPLY[@]}"')
printf '%s\n' "$got" | grep -q '^kapitza-upright' || fail "bash did not complete --preset kap: $got"
echo "check_package: bash completes --preset kap through the installed file"
if command -v zsh > /dev/null; then
  got=$(zsh -f -c 'compdef() { : }; _describe() { print -l -- ${(P)${@[-1]}} }
    source /usr/share/zsh/vendor-completions/_rattleback
    words=(rattleback --preset kap); CURRENT=3; _clap_dynamic_completer_rattleback')
  printf '%s\n' "$got" | grep -q '^kapitza-upright' || fail "zsh did not complete: $got"
  echo "check_package: zsh completes --preset kap through the installed file"
else
  echo "check_package: warning: zsh is not installed: not checked"
fi
if command -v fish > /dev/null; then
  got=$(fish -c "complete -C 'rattleback --preset kap'")
  printf '%s\n' "$got" | grep -q '^kapitza-upright' || fail "fish did not complete: $got"
  echo "check_package: fish completes --preset kap from vendor_completions.d"
else
  echo "check_package: warning: fish is not installed: not checked"
fi

dpkg -r rattleback > /dev/null
trap - EXIT
if command -v rattleback > /dev/null || [ -e /usr/share/man/man1/rattleback.1.gz ] \
  || [ -e /usr/share/bash-completion/completions/rattleback ] \
  || [ -e /usr/share/zsh/vendor-completions/_rattleback ] \
  || [ -e /usr/share/fish/vendor_completions.d/rattleback.fish ] \
  || [ -e /usr/share/doc/rattleback ]; then
  fail "removing the package left files behind"
fi
echo "check_package: removed cleanly"
