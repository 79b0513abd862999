"""A valid motion-model file of any size, for measuring a loader's memory (docs/dataset.md).

Takes a model from `patchflow train --gp spgp` and gives each of its three GPs M pseudo-inputs:
  python3 synthetic_model.py small.json big.json 2000 full    # full-precision numbers
  python3 synthetic_model.py small.json big.json 2000 digits  # 1-digit numbers (worst case)
The posterior is one a fit could give: W = eps * v v^T (full) or W = 0 (digits), both between 0
and (K_M + jitter)^-1, so `patchflow` loads the file. Standard library only.
"""
import json
import random
import sys

src, dst, m_count, mode = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
random.seed(1)
model = json.load(open(src))
for name in ["heading_sin", "heading_cos", "speed"]:
    gp = model[name]
    d = len(gp["input_names"])
    gp["signal_variance"] = 1.0
    gp["fit_report"]["m"] = m_count
    if mode == "digits":
        gp["pseudo_inputs"] = [[random.randint(0, 9) for _ in range(d)] for _ in range(m_count)]
        weights, var = [0] * m_count, [[0] * m_count for _ in range(m_count)]
    else:
        gp["pseudo_inputs"] = [[random.gauss(0, 1) for _ in range(d)] for _ in range(m_count)]
        v = [random.random() for _ in range(m_count)]
        eps = 0.5 / (m_count * sum(x * x for x in v) * 1.01)
        weights = [random.gauss(0, 1e-3) for _ in range(m_count)]
        var = [[eps * a * b for b in v] for a in v]
    gp["posterior"] = {"type": "sparse", "weights": weights, "var_matrix": var}
model.pop("extras", None)
with open(dst, "w") as f:
    json.dump(model, f, separators=(",", ":"))
