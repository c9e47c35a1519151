# Sourced by e2e.sh and floor_compare.sh: what both need to load a server the same way.

# utime + stime of a process, in clock ticks (getconf CLK_TCK a second).
cpu_ticks() {
  awk '{ print $14 + $15 }' "/proc/$1/stat"
}

# write_room_mode FILE N: a --modes file with one mode, "roomN": the asteroids preset without
# rocks, sandbox rules, N seats (the many-matches load).
write_room_mode() {
  echo "{\"modes\": [{\"name\": \"room$2\", \"preset\": \"asteroids\", \"rules\": \"sandbox\", \"max_players\": $2,
  \"world\": {\"rocks\": {\"count\": 0}}}]}" > "$1"
}
