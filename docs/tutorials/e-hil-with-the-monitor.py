# %% [markdown]
# # (e) Hardware in the loop with a simulated rig and the monitor
#
# In a HiL test the quarter car minus its damper runs in real time on the computer; its
# suspension stroke commands the rig's actuator, which moves the real damper, and the
# load cell's force closes the loop (Chapter 7, `docs/hil.md`). Without a rig at hand the
# toolkit's simulated rig stands in: the same loop, the same safety limits, a damper
# model behind an actuator and a load cell with their lags and noise.
#
# First a short run from Python, then the same loop driven through the browser monitor's
# HTTP API (the page at `http://127.0.0.1:PORT/` shows it live). The monitor needs the
# `web` extra: `pip install "mrsuspension[web]"`.

# %%
import json
import socket
import time
import urllib.request
from pathlib import Path

from matplotlib.figure import Figure

from mrsuspension.control import HiLo
from mrsuspension.engine import Simulation
from mrsuspension.excitation import Harmonic
from mrsuspension.hil import SimulatedRig, run_hil

out = Path("tutorial-output")
out.mkdir(exist_ok=True)
sim = Simulation(Harmonic(1.5, 0.01), controller=HiLo(1, mode="ACM"))  # 1.5 Hz, 10 mm
result = run_hil(sim, SimulatedRig(sim.damper), duration=1.0, rate=1000.0, out=out / "hil-run")
print(f"ended: {result.reason}")
print(result.stats.summary())

# %% [markdown]
# The recording holds every channel at the loop rate: the measured force `F_dm` and
# stroke `x_m` from the rig, the commanded stroke and current, the model's states.

# %%
rec = result.recording
print(f"{len(rec)} samples; channels: {', '.join(list(rec.channels)[:8])}, ...")
fig = Figure(figsize=(6, 3.2), layout="tight")
ax = fig.add_subplot()
ax.plot(rec["x_m"] * 1e3, rec["F_dm"], lw=0.8)
ax.set_xlabel("measured stroke $x_m$ [mm]")
ax.set_ylabel("measured force $F_{dm}$ [N]")
ax.set_title("the damper on the (simulated) rig, skyhook hi-lo")
fig.savefig(out / "e-hil-loop.png", dpi=80)
print(f"wrote {out / 'e-hil-loop.png'}")
fig  # a notebook shows the figure

# %% [markdown]
# ## The monitor
#
# `mrsus monitor` serves the monitor's page and API on 127.0.0.1 (here on a free port,
# its recordings in `tutorial-output/monitor`). Each run's loop gets its own process,
# never the server's. A script talks to it as the page does: state changes are JSON
# POSTs from the monitor's own origin (`docs/monitor.md`, "Security").

# %%
import signal
import subprocess
import sys

with socket.socket() as s:
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
base = f"http://127.0.0.1:{port}"
(out / "monitor").mkdir(exist_ok=True)
command = ["monitor", "--port", str(port), "--workdir", str(out / "monitor")]
server = subprocess.Popen(
    [sys.executable, "-m", "mrsuspension", *command],
    text=True,
    stdout=subprocess.PIPE,
    stderr=subprocess.STDOUT,
)


def api(path: str, body: dict | None = None) -> dict:
    """GET (or POST ``body`` as JSON) one API route; the JSON answer."""
    data = None if body is None else json.dumps(body).encode()
    headers = {"Content-Type": "application/json", "Origin": base}
    req = urllib.request.Request(base + path, data=data, headers=headers)
    with urllib.request.urlopen(req, timeout=30) as r:
        return json.loads(r.read())


deadline = time.monotonic() + 60.0  # the server imports the toolkit first
while True:
    try:
        laws = api("/api/controllers")["controllers"]
        break
    except OSError:
        if server.poll() is not None or time.monotonic() > deadline:
            raise RuntimeError(f"the monitor did not start: {server.communicate()[0]}") from None
        time.sleep(0.2)
print(f"mrsus {' '.join(command[:3])}: serving {base}/ ({len(laws)} control laws)")

# %% [markdown]
# Start a 1 s run of the skyhook hi-lo law, wait for it to end (the loop process starts
# and loads its compiled step first), and read what the monitor saw.

# %%
api("/api/start", {"duration": 1.0, "law": "skyhook-hilo", "mode": "ACM"})
status: dict = {}
deadline = time.monotonic() + 120.0
while time.monotonic() < deadline:
    status = api("/api/status")
    if status.get("state") in ("ended", "error") and "ticks" in status:
        break
    time.sleep(0.2)
print(f"state: {status.get('state')}, reason: {status.get('reason')}")
print(f"ticks {status.get('ticks')}, deadline misses {status.get('misses')}")
with urllib.request.urlopen(base + "/api/recording", timeout=30) as r:
    lines = r.read().decode().splitlines()
print(f"recording: {len(lines) - 1} rows; columns {lines[0][:60]}...")

# %% [markdown]
# Stop the server as Ctrl-C does (SIGINT): a run still going would be taken to its safe
# state first (current 0, actuator to mid-stroke). The exit code is the command line's
# for an interrupt, 130 (128 + SIGINT).

# %%
server.send_signal(signal.SIGINT)
code = server.wait(timeout=60)
print(f"monitor stopped, exit code {code}; it said: {server.communicate()[0].strip()}")
