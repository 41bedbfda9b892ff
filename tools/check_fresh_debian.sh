#!/usr/bin/env bash
# The fresh-machine check: does a new user's Debian 12 go from clone to result with the
# README's two commands? Makes a minimal bookworm root (debootstrap --variant=minbase,
# nothing installed by hand), copies a clean clone of HEAD into it, and runs
# tools/demo.sh, then tools/test.sh, then the README's Python example inside it with chroot. A package missing from
# tools/debian-packages.txt fails here even when this machine happens to have it.
#
# usage: tools/check_fresh_debian.sh [--keep] [--root DIR]
#   --keep      leave the root in place afterwards (for a look inside)
#   --root DIR  where to build the root (default: a new folder under /var/tmp)
# Needs root. The base system's packages are cached as a tarball in
# ${MFP_CACHE_DIR:-~/.cache/mfp}/ so later runs skip that download. The Debian mirror is
# the one this machine's own apt sources name. Ends with one line: 'fresh Debian check:
# passed' or 'fresh Debian check: FAILED at STEP: REASON'. Mounts are undone on every exit.
set -uo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
keep=0
root=""
while (($#)); do
  case "$1" in
    --keep) keep=1 ;;
    --root) shift; root="${1:?--root needs a folder}" ;;
    -h|--help) sed -n '2,15p' "${BASH_SOURCE[0]}"; exit 0 ;;
    *) echo "check_fresh_debian: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done

say() { printf '[fresh debian] %s\n' "$*"; }
step_name="setup"
fail() {
  echo "fresh Debian check: FAILED at $step_name: $*"
  exit 1
}

[ "$(id -u)" -eq 0 ] || { step_name="start"; fail "needs root (debootstrap and chroot); run it as root"; }

# The mirror: the first Debian archive URI in this machine's apt sources (deb822 or
# one-line format), so the check uses the same archive the machine itself installs from.
mirror="$(grep -hE '^\s*(URIs:|deb\s)' /etc/apt/sources.list.d/*.sources /etc/apt/sources.list 2>/dev/null \
  | grep -v -- '-security' | grep -oE 'https?://[^ ]+' | head -n 1)"
mirror="${mirror:-http://deb.debian.org/debian}"

cache="${MFP_CACHE_DIR:-$HOME/.cache/mfp}"
tarball="$cache/debootstrap-bookworm-minbase.tgz"
root="${root:-$(mktemp -d /var/tmp/mfp-fresh-debian.XXXXXX)}"
mounted=()

cleanup() {
  local m
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
    m="${mounted[$i]}"
    umount -l "$m" 2>/dev/null || true
  done
  if ((keep)); then
    say "root kept at $root"
  elif [ -n "$root" ] && [ -d "$root" ]; then
    # Only after every mount is gone: never delete through a bind mount.
    if ! grep -q " $root" /proc/mounts; then rm -rf --one-file-system "$root"; fi
  fi
}
trap cleanup EXIT
trap 'step_name="$step_name (interrupted)"; fail "signal"' INT TERM

timed() {  # timed NAME COMMAND...: runs a step, prints its time, fails the check on error
  step_name="$1"; shift
  local start=$SECONDS log="$cache/fresh-debian-$step_name.log"
  say "$step_name ..."
  if "$@" >"$log" 2>&1; then
    say "$step_name: $((SECONDS - start)) s"
  else
    local code=$?
    say "$step_name: failed after $((SECONDS - start)) s (exit $code); last lines of $log:"
    tail -n 25 "$log" | sed 's/^/    /'
    local why
    # The most telling line first: a missing library, then a compile error, then any failure.
    why="$(grep -m1 -E 'cannot find -l' "$log" ||
           { grep -q 'The following tests FAILED' "$log" &&
             echo "tests failed:$(sed -n '/The following tests FAILED/,$p' "$log" | grep -E '^\s+[0-9]+ - ' | sed -E 's/^\s+[0-9]+ - / /; s/ \(.*//' | tr '\n' ',')"; } ||
           grep -m1 -E 'error:|FAILED|failed' "$log")"
    why="$(cut -c1-200 <<<"$why")"
    fail "${why:-exit $code, see $log}"
  fi
}

mkdir -p "$cache"
say "repository $repo at $(git -C "$repo" rev-parse --short HEAD); mirror $mirror; root $root"

if ! command -v debootstrap >/dev/null; then
  timed install-debootstrap bash -c 'apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq debootstrap'
fi

if [ ! -s "$tarball" ]; then
  tmp_root="$(mktemp -d /var/tmp/mfp-debootstrap-download.XXXXXX)"
  timed download-base debootstrap --variant=minbase --make-tarball="$tarball.part" bookworm "$tmp_root" "$mirror"
  rm -rf "$tmp_root"
  mv "$tarball.part" "$tarball"
else
  say "base packages cached: $tarball"
fi
timed make-root debootstrap --variant=minbase --unpack-tarball="$tarball" bookworm "$root" "$mirror"

# A clean clone of HEAD: what a user gets, with nothing untracked or ignored.
timed copy-clone git clone -q --no-hardlinks "$repo" "$root/mfp"

cp /etc/resolv.conf "$root/etc/resolv.conf"
for m in proc sys dev dev/pts; do
  mkdir -p "$root/$m"
  case "$m" in
    proc) mount -t proc proc "$root/proc" ;;
    sys) mount -t sysfs sysfs "$root/sys" ;;
    *) mount --bind "/$m" "$root/$m" ;;
  esac || fail "could not mount /$m in the root"
  mounted+=("$root/$m")
done

# The machine's own way out to the package registries (its CA bundle, proxies, pip
# index), as a user's machine has its own: the zoo test installs a PyPI package, and a
# network that inspects TLS needs its CA. Nothing of mfp's is carried in.
net_env=()
if [ -s /etc/ssl/certs/ca-certificates.crt ]; then
  cp /etc/ssl/certs/ca-certificates.crt "$root/etc/host-ca-bundle.crt"
  net_env+=(SSL_CERT_FILE=/etc/host-ca-bundle.crt PIP_CERT=/etc/host-ca-bundle.crt
            REQUESTS_CA_BUNDLE=/etc/host-ca-bundle.crt)
fi
for v in http_proxy https_proxy no_proxy HTTP_PROXY HTTPS_PROXY NO_PROXY PIP_INDEX_URL PIP_DEFAULT_TIMEOUT; do
  [ -n "${!v:-}" ] && net_env+=("$v=${!v}")
done
in_root() {
  chroot "$root" /usr/bin/env -i HOME=/root PATH=/usr/sbin:/usr/bin:/sbin:/bin LANG=C.UTF-8 CI="${CI:-}" \
    "${net_env[@]}" "$@"
}
timed demo in_root bash -c 'cd /mfp && tools/demo.sh'
timed test in_root bash -c 'cd /mfp && tools/test.sh'
# The README's Python example, as a new user runs it after the two commands.
timed example in_root bash -c 'cd /mfp && PYTHONPATH=build/python python3 examples/plan_on_stairs.py --out /tmp/stairs.png'
step_name="done"
echo "fresh Debian check: passed (demo, the whole suite and the Python example on a fresh bookworm, $SECONDS s in all)"
