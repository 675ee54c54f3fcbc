# Reads this machine's own apt configuration, so that scripts that bootstrap a Debian root
# use the mirror and proxy the machine already uses (a local mirror, a proxy) and name no
# host of their own. Source it; bash only.

# debian_mirror SUITE: the first enabled "deb" source offering SUITE (e.g. bookworm), from
# /etc/apt/sources.list.d/*.sources (deb822), then *.list and /etc/apt/sources.list
# (one-line). Prints the URI; fails with a message naming the files read if none does.
debian_mirror() {
  local suite=$1 dir=${APT_SOURCES_DIR:-/etc/apt} uri
  uri=$(
    {
      for f in "$dir"/sources.list.d/*.sources; do [ -f "$f" ] && cat "$f" && echo; done
    } | awk -v suite="$suite" '
      function flush() {
        if (types ~ /(^| )deb( |$)/ && (" " suites " ") ~ (" " suite " ") && enabled != "no" && uris != "") {
          split(uris, u, " "); print u[1]; found = 1; exit
        }
        types = ""; suites = ""; uris = ""; enabled = ""
      }
      /^[ \t]*#/ { next }
      /^[ \t]*$/ { flush(); next }
      tolower($1) == "types:"   { $1 = ""; types = $0 }
      tolower($1) == "uris:"    { $1 = ""; uris = $0 }
      tolower($1) == "suites:"  { $1 = ""; suites = $0 }
      tolower($1) == "enabled:" { enabled = tolower($2) }
      END { if (!found) flush() }'
  )
  if [ -z "$uri" ]; then
    uri=$(
      for f in "$dir"/sources.list.d/*.list "$dir"/sources.list; do [ -f "$f" ] && cat "$f"; done |
        sed -e 's/#.*//' -e 's/\[[^]]*\]//' | awk -v suite="$suite" '$1 == "deb" && $3 == suite { print $2; exit }'
    )
  fi
  if [ -z "$uri" ]; then
    echo "no enabled apt source offers '$suite' in $dir/sources.list.d/*.sources, *.list or $dir/sources.list;" \
      "add one (or point APT_SOURCES_DIR at a directory that has one)" >&2
    return 1
  fi
  echo "${uri%/}"
}

# apt_http_proxy: the HTTP proxy apt is configured with (Acquire::http::Proxy), or nothing.
apt_http_proxy() {
  local proxy=""
  eval "$(apt-config shell proxy Acquire::http::Proxy 2>/dev/null)"
  [ "$proxy" = DIRECT ] && proxy=""
  echo "$proxy"
}
