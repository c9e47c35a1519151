# Arena game server image. The build stage runs exactly what CI runs (make deps build test);
# the runtime stage holds only the programs (they link nothing beyond the C++ runtime).
FROM debian:bookworm AS build
RUN apt-get update \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends make \
 && rm -rf /var/lib/apt/lists/*
WORKDIR /src
COPY . .
RUN make deps build test

FROM debian:bookworm-slim AS runtime
RUN useradd --system --uid 10001 --no-create-home arena
COPY --from=build /src/build/bin/arena-server /src/build/bin/arena-replay /src/build/bin/arena-sim /usr/local/bin/
USER arena
EXPOSE 7777/tcp
STOPSIGNAL SIGTERM
# PID 1 in exec form, so that SIGTERM reaches the server and it drains cleanly.
ENTRYPOINT ["/usr/local/bin/arena-server", "--bind", "0.0.0.0", "--port", "7777"]
