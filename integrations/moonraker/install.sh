#!/usr/bin/env bash
# Installs scaffold's Moonraker component on a Klipper host (a Raspberry Pi
# running Moonraker, as MainsailOS, FluiddPi or KIAUH set it up):
#  - links scaffold.py (beside this script) into moonraker/components/;
#  - with --binary, puts the executable in ~/scaffold/ with the
#    release_info.json Moonraker's update manager reads for "executable"
#    programs;
#  - adds a [scaffold] section and an [update_manager scaffold] section
#    (type: executable) to moonraker.conf, each only if it is not there;
#  - restarts Moonraker (not with --no-restart).
# Running it again changes nothing. Usage:
#   install.sh [--binary FILE] [--repo OWNER/NAME] [--moonraker DIR]
#              [--config FILE] [--no-restart]
# Defaults: --moonraker ~/moonraker, --config ~/printer_data/config/moonraker.conf.
set -euo pipefail
here="$(cd "$(dirname "$(readlink -f "$0")")" && pwd)"
moonraker="$HOME/moonraker"
conf="$HOME/printer_data/config/moonraker.conf"
binary=""
repo=""
restart=1
while [ $# -gt 0 ]; do
  case "$1" in
    --binary) binary="$2"; shift 2 ;;
    --repo) repo="$2"; shift 2 ;;
    --moonraker) moonraker="$2"; shift 2 ;;
    --config) conf="$2"; shift 2 ;;
    --no-restart) restart=0; shift ;;
    -h|--help) sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "install.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
components="$moonraker/moonraker/components"
[ -d "$components" ] || { echo "install.sh: no Moonraker at $moonraker ($components is missing); give --moonraker DIR" >&2; exit 1; }
[ -f "$conf" ] || { echo "install.sh: no $conf; give --config FILE" >&2; exit 1; }

# The release file that runs on this board (static: the kernel decides).
case "$(uname -m)" in
  aarch64|arm64) asset=scaffold-linux-aarch64 ;;
  armv7*|armv8l) asset=scaffold-linux-armhf ;;
  *) asset="" ;;
esac

ln -sfn "$here/scaffold.py" "$components/scaffold.py"
echo "linked $components/scaffold.py -> $here/scaffold.py"

exe=""
if [ -n "$binary" ]; then
  # Named as the release asset it is (Moonraker downloads that name).
  name="$(basename "$binary")"
  case "$name" in scaffold-linux-*) asset="$name" ;; esac
  [ -n "$asset" ] || { echo "install.sh: no scaffold release file for $(uname -m); give one named scaffold-linux-ARCH" >&2; exit 1; }
  version="$("$binary" --version | sed -n 's/^scaffold \([0-9.]*\).*/\1/p')"
  [ -n "$version" ] || { echo "install.sh: $binary --version does not run on this board" >&2; exit 1; }
  mkdir -p "$HOME/scaffold"
  if [ "$(readlink -f "$binary")" != "$(readlink -f "$HOME/scaffold/$asset")" ]; then
    install -m 755 "$binary" "$HOME/scaffold/$asset"
  fi
  owner="${repo%%/*}"; project="${repo#*/}"
  [ -n "$repo" ] || { owner=scaffold; project=scaffold; }
  printf '{"project_name": "%s", "project_owner": "%s", "version": "v%s", "asset_name": "%s"}\n' \
    "$project" "$owner" "$version" "$asset" > "$HOME/scaffold/release_info.json"
  exe="$HOME/scaffold/$asset"
  echo "installed scaffold $version as $exe"
elif command -v scaffold >/dev/null; then
  exe="$(command -v scaffold)"   # the .deb's /usr/bin/scaffold
else
  echo "install.sh: no scaffold executable: give --binary FILE or install the .deb" >&2; exit 1
fi

if ! grep -q '^\[scaffold\]' "$conf"; then
  cat >> "$conf" <<EOF

[scaffold]
# scaffold adds supports to each uploaded G-code file (integrations/moonraker)
path: ${exe/#$HOME/\~}
method: scaffold
# options: --overhang-angle 50
enabled: True
timeout: 600
EOF
  echo "added [scaffold] to $conf"
fi

if [ -n "$binary" ] && [ -n "$repo" ] && ! grep -q '^\[update_manager scaffold\]' "$conf"; then
  cat >> "$conf" <<EOF

[update_manager scaffold]
type: executable
channel: stable
repo: $repo
path: ~/scaffold
is_system_service: False
EOF
  echo "added [update_manager scaffold] to $conf"
  grep -q '^\[update_manager\]' "$conf" || echo "note: $conf has no [update_manager] section: updates need one" >&2
fi

if [ "$restart" -eq 1 ]; then
  echo "restarting Moonraker"
  sudo systemctl restart moonraker
fi
