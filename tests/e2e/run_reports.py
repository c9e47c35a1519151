"""What bench/loss.sh keeps of each run (LOSS_WORK): the bots' --json and the server's --stats-json."""
import json


def load(path):
    """The report at `path`, or {"error": why} when it is missing or not JSON."""
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        return {"error": str(e)}
