"""GPy FITC vs patchflow SPGP objective + gradient at N=1600, M=100, D=242, side by side in one
run: rounds alternate between the two; per round each side runs 4 sub-rounds of 5 evaluations in a
warm process and reports its best sub-round (the same protocol for both). Prints min and median."""
import json, subprocess, sys, time
import numpy as np
import GPy

rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 10
binary = sys.argv[2]
n, d, m, evals = 1600, 242, 100, 5
rng = np.random.default_rng(1)
x = rng.uniform(-1, 1, size=(n, d))
y = np.sin(2 * x[:, 0]) + x[:, 1] * x[:, 2] + 0.1 * rng.uniform(-1, 1, size=n)
x = (x - x.mean(0)) / x.std(0)
y = ((y - y.mean()) / y.std())[:, None]
z = x[rng.permutation(n)[:m]]
kern = GPy.kern.RBF(d, variance=1.0, lengthscale=np.full(d, np.sqrt(d)), ARD=True)
lik = GPy.likelihoods.Gaussian(variance=0.25)
model = GPy.core.SparseGP(x, y, z, kern, lik,
                          inference_method=GPy.inference.latent_function_inference.FITC())
theta = model.optimizer_array.copy()
model._objective_grads(theta)
gpy, ours = [], []
for r in range(rounds):
    best = float("inf")
    for _ in range(4):
        t = time.perf_counter()
        for _ in range(evals):
            theta[0] += 1e-9
            model._objective_grads(theta)
        best = min(best, 1e3 * (time.perf_counter() - t) / evals)
    gpy.append(best)
    out = subprocess.run([binary, str(n), str(d), str(m), "4", str(evals)], capture_output=True,
                         text=True, check=True).stdout.strip().splitlines()[-1]
    ours.append(json.loads(out)["ms_min"])
    print(f"round {r}: GPy {gpy[-1]:.1f} ms, ours {ours[-1]:.2f} ms", flush=True)
res = {"gpy_ms_min": min(gpy), "gpy_ms_median": float(np.median(gpy)),
       "ours_ms_min": min(ours), "ours_ms_median": float(np.median(ours)),
       "speedup_min": min(gpy) / min(ours), "speedup_median": float(np.median(gpy) / np.median(ours))}
print(json.dumps(res))
