"""Where the peer codes' drivers and stored results are: ../shared/peers next to the project root, or
the folder named by the environment variable VOFDEM_PEERS (see that folder's README for installing the
peers and running them)."""
import os
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def peers_dir() -> Path:
    """The peers' folder: $VOFDEM_PEERS if set, else ../shared/peers relative to the project root."""
    env = os.environ.get("VOFDEM_PEERS")
    return Path(env) if env else ROOT.parent / "shared" / "peers"
