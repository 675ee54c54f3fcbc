# scripts/lib/compose_images.sh: the images scripts/compose-check needs before it builds its
# own, sourced by it (its say, fail, need and $logs). compose_base_image: debian:bookworm
# (and :bookworm-slim) from debootstrap when Docker has none, through this machine's Debian
# mirror and proxy, checked against the suite's record of its packages.
# compose_postgres_image: postgres:15, or the stand-in docker/postgres through
# DTMF_POSTGRES_IMAGE when it cannot be pulled.

compose_base_image() {
  local mirror proxy root f present lacking
  if ! docker image inspect debian:bookworm >/dev/null 2>&1; then
    need debootstrap debootstrap
    mirror=$(debian_mirror bookworm) || fail "no Debian 12 mirror in this machine's apt sources"
    proxy=$(apt_http_proxy)
    root=$(mktemp -d /tmp/compose-check-root.XXXXXX)
    say "no image debian:bookworm: debootstrap --variant=minbase bookworm from $mirror${proxy:+ through $proxy} (a few minutes)"
    http_proxy=$proxy debootstrap --variant=minbase bookworm "$root" "$mirror" >"$logs/debootstrap.log" 2>&1 ||
      { tail -n 20 "$logs/debootstrap.log" >&2; rm -rf "$root"; fail "debootstrap failed"; }
    # The image's apt reaches Debian as this machine does: its sources, its proxy.
    rm -f "$root/etc/apt/sources.list"
    for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list /etc/apt/sources.list.d/*.sources; do
      [ -f "$f" ] && cp "$f" "$root$f"
    done
    [ -z "$proxy" ] || echo "Acquire::http::Proxy \"$proxy\";" >"$root/etc/apt/apt.conf.d/00proxy"
    rm -rf "$root"/var/lib/apt/lists/* "$root"/var/cache/apt/*.bin "$root"/var/cache/apt/archives/*.deb
    say "docker import: debian:bookworm, tagged debian:bookworm-slim too"
    tar -C "$root" -c . | docker import - debian:bookworm >/dev/null || { rm -rf "$root"; fail "docker import failed"; }
    rm -rf "$root"
  fi
  docker image inspect debian:bookworm-slim >/dev/null 2>&1 || docker tag debian:bookworm debian:bookworm-slim
  say "base image: debian:bookworm $(docker image inspect -f '{{.Id}}' debian:bookworm | cut -c1-19)"
  # The suite's docker.runtime_packages test takes tests/docker/bookworm-slim-packages for what
  # this image has: it must name nothing the image lacks.
  # shellcheck disable=SC2016  # expanded by dpkg-query
  present=$(docker run --rm debian:bookworm-slim dpkg-query -W -f='${Package}\n') || fail "cannot list debian:bookworm-slim's packages"
  lacking=$(grep -v '^#' tests/docker/bookworm-slim-packages | sort -u | comm -23 - <(sort -u <<<"$present") | paste -sd ' ' -)
  [ -z "$lacking" ] || fail "tests/docker/bookworm-slim-packages names packages debian:bookworm-slim lacks: $lacking (regenerate it as its header says)"
  say "base image: has all $(grep -vc '^#' tests/docker/bookworm-slim-packages) packages tests/docker/bookworm-slim-packages names"
}

compose_postgres_image() {
  if [ -n "${DTMF_POSTGRES_IMAGE:-}" ]; then
    say "PostgreSQL: $DTMF_POSTGRES_IMAGE (DTMF_POSTGRES_IMAGE from the caller)"
  elif docker image inspect postgres:15 >/dev/null 2>&1; then
    say "PostgreSQL: postgres:15 (present)"
  elif timeout 60 docker pull -q postgres:15 >"$logs/pull.log" 2>&1; then
    say "PostgreSQL: postgres:15 (pulled)"
  else
    say "postgres:15 cannot be pulled ($(tail -n 1 "$logs/pull.log")); building the stand-in docker/postgres"
    show docker build -t dtmf-postgres:15 docker/postgres
    docker build -t dtmf-postgres:15 docker/postgres >"$logs/postgres-build.log" 2>&1 ||
      { tail -n 30 "$logs/postgres-build.log" >&2; fail "the stand-in PostgreSQL image did not build"; }
    export DTMF_POSTGRES_IMAGE=dtmf-postgres:15
    say "PostgreSQL: DTMF_POSTGRES_IMAGE=$DTMF_POSTGRES_IMAGE"
  fi
}
