# %% [markdown]
# # gyrovib in a notebook
#
# A notebook-style example (cells marked `# %%`, as Jupytext, VS Code and
# Spyder read them; `python docs/notebook.py` runs it top to bottom, and
# tests/test_notebook.py does so on every test run). It needs the `pandas`
# and `plot` extras: `pip install 'gyrovib[pandas,plot]'`.
#
# Set `GYROVIB_PLOT` to the PNG file the plot should go to (default:
# `notebook-sweep.png` in the working directory).

# %%
import os

import matplotlib

matplotlib.use("Agg")  # no display needed; in Jupyter, leave the default backend
import matplotlib.pyplot as plt

import gyrovib

# %% [markdown]
# ## Load the bundled catalogues
# `gyrovib.load()` with no argument gives the nine bundled sensors and fourteen
# profiles; give paths to load your own, or both: `gyrovib.load("mine.yaml",
# bundled="sensors")`. Printing the catalogue gives one line.

# %%
catalog = gyrovib.load()
print(catalog)
print([entry.sensor.id for entry in catalog.sensors])
print([entry.profile.id for entry in catalog.profiles])

# %% [markdown]
# ## Compare two parts
# Two MEMS gyroscopes under every profile, in deg/h: `to_frame()` gives one
# row per sensor × profile, columns named as in `gyrovib analyze --format csv`.

# %%
parts = ["adxrs645", "sch16t"]
analysis = gyrovib.analyze(catalog, sensors=parts, unit="deg/h").to_frame()
table = analysis.pivot(index="profile", columns="sensor", values="rms")
print(table.round(3))

# %%
# Which part keeps the larger margin against a 10 deg/h budget, profile by profile?
selection = gyrovib.select(catalog, sensors=parts, budget="10deg/h", unit="deg/h").to_frame()
margins = selection.pivot(index="profile", columns="sensor", values="margin")
better = margins.idxmax(axis=1)
print(margins.round(2))
print(better.value_counts())
# The verdict column is `passed` (the JSON's `pass`); `status` says pass, fail or
# unverified (a datasheet figure that is not published could decide it).
print(selection.query("not passed")[["sensor", "profile", "status"]].head())

# %% [markdown]
# ## Plot one DataFrame
# The error of both parts over the carrier rate Ω_K3 under one profile.

# %%
sweep = gyrovib.sweep(catalog, rates=(-100, 100), points=201, sensors=parts,
                      profiles="flat-random-hover").to_frame()
figure, axes = plt.subplots(figsize=(7, 4))
for sensor, rows in sweep.groupby("sensor"):
    axes.semilogy(rows["rate_x3"], rows["exact_rms"], label=sensor)
axes.set_xlabel("Ω_K3 (deg/s)")
axes.set_ylabel("Δ_V(RMS) (deg/s)")
axes.set_title("flat-random-hover: error over the carrier rate")
axes.legend()
figure.tight_layout()
target = os.environ.get("GYROVIB_PLOT", "notebook-sweep.png")
figure.savefig(target)
plt.close(figure)
print("plotted to", target)
