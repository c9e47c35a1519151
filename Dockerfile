# Arena game server image. The build stage runs exactly what CI runs (make deps build test);
# the runtime stage holds only the programs and the one shared library they need beyond the C++
# runtime (libsodium, for signed join tokens; libenet7, for the UDP transport).
FROM debian:bookworm AS build
RUN apt-get update \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends make \
 && rm -rf /var/lib/apt/lists/*
WORKDIR /src
COPY . .
RUN make deps build test

FROM debian:bookworm-slim AS runtime
RUN apt-get update \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends libsodium23 libenet7 \
 && rm -rf /var/lib/apt/lists/* \
 && useradd --system --uid 10001 --no-create-home arena
COPY --from=build /src/build/bin/arena-server /src/build/bin/arena-replay /src/build/bin/arena-sim \
     /src/build/bin/arena-token /src/build/bin/arena-healthcheck /usr/local/bin/
# The page that plays the game, served at / with --http-port (the default web root for a
# program in /usr/local/bin is /usr/local/web or /usr/local/share/arena/web).
COPY --from=build /src/build/web /usr/local/share/arena/web
USER arena
# 7777: the game (TCP; UDP too when started with --udp-port 7777). 8080: /metrics and /healthz (HTTP), for Prometheus and the probes.
EXPOSE 7777/tcp 7777/udp 8080/tcp
STOPSIGNAL SIGTERM
# /healthz answers 200 only while the tick loop advances, so a wedged server turns unhealthy
# even though its sockets still accept. The probe is our own arena-healthcheck (the slim image
# has no curl, and should not carry curl's TLS stack for a loopback GET). No --start-period:
# the server answers from its first second, and dockerfilelint rejects the flag.
HEALTHCHECK --interval=5s --timeout=3s --retries=3 \
  CMD ["/usr/local/bin/arena-healthcheck", "http://127.0.0.1:8080/healthz", "--timeout", "2"]
# PID 1 in exec form, so that SIGTERM reaches the server and it drains cleanly.
ENTRYPOINT ["/usr/local/bin/arena-server", "--bind", "0.0.0.0", "--port", "7777", "--metrics-port", "8080"]
