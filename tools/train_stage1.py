#!/usr/bin/env python3
"""Train an agent on TurtleBot3Stage1-v0 with stable-baselines3 and log its goal rate.

    make train                                   # installs the train extra, then this script
    python3 tools/train_stage1.py --steps 60000 --algo dqn --out catkin_ws/train

Needs the train extra (bash tools/install_extra.sh train: stable-baselines3, a CPU build of
torch, matplotlib); the simulator and the lab do not.

Every ``--log-every`` environment steps it writes one CSV row (OUT/stage1_<algo>.csv):

- ``env_steps``: environment steps so far, all environments together (one step = 0.2 s of sim)
- ``wall_s``: wall-clock seconds since training began (environment creation excluded)
- ``goals``, ``collisions``, ``timeouts``: how each goal attempt of the window ended: a goal
  reached (the next goal follows in the same episode), a collision (the episode ends) or the
  501-step limit (the episode ends)
- ``goal_rate``: goals / (goals + collisions + timeouts) in the window, 0 to 1; empty when
  no attempt ended in the window
- ``goals_per_1k``: goals per 1000 environment steps in the window (how fast goals come)
- ``episodes``, ``mean_return``: episodes that ended in the window and their mean return

and at the end a PNG plot (OUT/learning_stage1.png, or ``--plot``) of the goal rate against
environment steps and wall time (when matplotlib imports), then one summary line.
"""
import argparse
import csv
import importlib
import os
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MISSING = ("train_stage1: %s is not installed: run 'bash tools/install_extra.sh train' "
           "(or 'make train')")


def parse_args(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--algo", choices=("dqn", "ppo"), default="dqn")
    parser.add_argument("--steps", type=int, default=60000,
                        help="environment steps in all (default 60000)")
    parser.add_argument("--envs", type=int, default=1,
                        help="environments stepped together (PPO: in subprocesses; default 1)")
    parser.add_argument("--log-every", type=int, default=2000,
                        help="environment steps per CSV row (default 2000)")
    parser.add_argument("--time-step", type=float, default=0.0025,
                        help="physics step in s (default 0.0025, the sim node's)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", default=os.path.join(ROOT, "catkin_ws", "train"),
                        help="folder for the CSV, the plot and the model")
    parser.add_argument("--plot", default=None, help="PNG path (default OUT/learning_stage1.png)")
    parser.add_argument("--threads", type=int, default=1, help="torch threads (default 1)")
    parser.add_argument("--replot", metavar="CSV", default=None,
                        help="only draw the plot of an earlier run's CSV, and stop")
    return parser.parse_args(argv)


class GoalLog:
    """Counts how goal attempts end and writes a CSV row every ``every`` environment steps."""

    FIELDS = ("env_steps", "wall_s", "goals", "collisions", "timeouts", "goal_rate",
              "goals_per_1k", "episodes", "mean_return")

    def __init__(self, path, every, n_envs):
        self.path, self.every, self.n_envs = path, every, n_envs
        self.rows = []
        self.steps = 0
        self._last = 0                     # env_steps at the last row
        self.started = time.monotonic()
        self._returns = [0.0] * n_envs
        self._clear()
        with open(self.path, "w", newline="") as handle:
            csv.writer(handle).writerow(self.FIELDS)

    def _clear(self):
        self.goals = self.collisions = self.timeouts = 0
        self.ended = []

    def record(self, rewards, dones, infos):
        """One vector step: ``rewards`` and ``dones`` per environment, SB3's ``infos``."""
        for i, (reward, done, info) in enumerate(zip(rewards, dones, infos)):
            self.steps += 1
            self._returns[i] += float(reward)
            if info.get("at_goal"):
                self.goals += 1
            if done:
                if info.get("collision"):
                    self.collisions += 1
                else:
                    self.timeouts += 1   # TimeLimit.truncated: the 501-step limit
                self.ended.append(self._returns[i])
                self._returns[i] = 0.0
            if self.steps % self.every == 0:
                self.flush()

    def flush(self):
        attempts = self.goals + self.collisions + self.timeouts
        row = {"env_steps": self.steps, "wall_s": round(time.monotonic() - self.started, 1),
               "goals": self.goals, "collisions": self.collisions, "timeouts": self.timeouts,
               "goal_rate": round(self.goals / attempts, 3) if attempts else "",
               "goals_per_1k": round(1000.0 * self.goals / max(self.steps - self._last, 1),
                                     1),
               "episodes": len(self.ended),
               "mean_return": round(sum(self.ended) / len(self.ended), 1) if self.ended else ""}
        self._last = self.steps
        self.rows.append(row)
        with open(self.path, "a", newline="") as handle:
            csv.DictWriter(handle, self.FIELDS).writerow(row)
        print("steps %7d  wall %6.0f s  goals %3d  collisions %3d  timeouts %2d  goal rate %s"
              % (row["env_steps"], row["wall_s"], row["goals"], row["collisions"],
                 row["timeouts"], row["goal_rate"]), flush=True)
        self._clear()


def plot(rows, path, title):
    """Goal rate against environment steps and wall time, as a small PNG; False without
    matplotlib."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return False
    rows = [r for r in rows if r["goal_rate"] != ""]
    rate = [float(r["goal_rate"]) for r in rows]
    fast = [float(r["goals_per_1k"]) for r in rows]
    fig, panels = plt.subplots(1, 2, figsize=(8.0, 3.4), dpi=80, sharey=True)
    xs = ([int(r["env_steps"]) / 1000.0 for r in rows], [float(r["wall_s"]) / 60.0 for r in rows])
    labels = ("environment steps (thousands; 1 step = 0.2 s sim)", "wall time (min, this machine)")
    for ax, x, label in zip(panels, xs, labels):
        ax.plot(x, rate, marker="o", markersize=3, label="goal rate (left axis)")
        ax.set_xlabel(label)
        ax.set_ylim(0, 1.02)
        ax.grid(alpha=0.3)
        twin = ax.twinx()
        twin.plot(x, fast, color="tab:orange", linestyle="--", label="goals / 1000 steps")
        twin.set_ylim(0, max(fast + [1.0]) * 1.1)
        if ax is panels[-1]:
            twin.set_ylabel("goals per 1000 steps (dashed)")
    panels[0].set_ylabel("goal rate (goals / attempts)")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    return True


def make_stage1(time_step):
    """One TurtleBot3Stage1-v0 (a function, so that SB3 adds no render_mode)."""
    import gymnasium
    importlib.import_module("tutorial_turtlebot.learning")  # registers TurtleBot3Stage1-v0

    return gymnasium.make("TurtleBot3Stage1-v0", time_step=time_step)


def main(argv=None):
    args = parse_args(argv)
    if args.replot:
        with open(args.replot, newline="") as handle:
            rows = list(csv.DictReader(handle))
        path = args.plot or os.path.join(os.path.dirname(args.replot), "learning_stage1.png")
        if not plot(rows, path, "%s on TurtleBot3Stage1-v0 (stable-baselines3)"
                    % os.path.basename(args.replot)[len("stage1_"):-len(".csv")].upper()):
            print(MISSING % "matplotlib", file=sys.stderr)
            return 2
        print("train_stage1: plot of %s in %s" % (args.replot, path))
        return 0
    for module in ("torch", "stable_baselines3"):
        try:
            __import__(module)
        except ImportError:
            print(MISSING % module, file=sys.stderr)
            return 2
    import torch
    from stable_baselines3 import DQN, PPO
    from stable_baselines3.common.callbacks import BaseCallback
    from stable_baselines3.common.env_util import make_vec_env
    from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv

    torch.set_num_threads(args.threads)
    os.makedirs(args.out, exist_ok=True)
    env_id = "TurtleBot3Stage1-v0"
    vec_cls = SubprocVecEnv if args.envs > 1 else DummyVecEnv
    env = make_vec_env(make_stage1, n_envs=args.envs, seed=args.seed, vec_env_cls=vec_cls,
                       env_kwargs={"time_step": args.time_step})
    if args.algo == "dqn":
        # ROBOTIS' agent: discount 0.99, batch 64, a 2-layer MLP; a faster epsilon schedule
        # (over a fifth of the run) and a smaller target-update period than its 2000.
        model = DQN("MlpPolicy", env, learning_rate=5e-4, buffer_size=100000,
                    learning_starts=1000, batch_size=64, gamma=0.99, train_freq=4,
                    target_update_interval=1000, exploration_fraction=0.2,
                    exploration_final_eps=0.05, policy_kwargs={"net_arch": [64, 64]},
                    seed=args.seed, verbose=0)
    else:
        model = PPO("MlpPolicy", env, n_steps=1024 // args.envs, batch_size=128,
                    learning_rate=3e-4, gamma=0.99, ent_coef=0.01,
                    policy_kwargs={"net_arch": [64, 64]}, seed=args.seed, verbose=0)

    csv_path = os.path.join(args.out, "stage1_%s.csv" % args.algo)
    log = GoalLog(csv_path, args.log_every, args.envs)

    class Callback(BaseCallback):
        def _on_step(self):
            log.record(self.locals["rewards"], self.locals["dones"], self.locals["infos"])
            return True

    print("train_stage1: %s on %s, %d env(s), %d steps, time_step %g s, torch %s"
          % (args.algo.upper(), env_id, args.envs, args.steps, args.time_step,
             torch.__version__), flush=True)
    model.learn(total_timesteps=args.steps, callback=Callback())
    if log.steps % args.log_every:
        log.flush()
    wall = time.monotonic() - log.started
    model.save(os.path.join(args.out, "stage1_%s" % args.algo))
    env.close()
    plot_path = args.plot or os.path.join(args.out, "learning_stage1.png")
    title = "%s on %s (stable-baselines3), %d env(s)" % (args.algo.upper(), env_id, args.envs)
    drew = plot(log.rows, plot_path, title)
    rated = [r for r in log.rows if r["goal_rate"] != ""]
    first = rated[0]["goal_rate"] if rated else float("nan")
    last = rated[-1]["goal_rate"] if rated else float("nan")
    best = max((r["goal_rate"] for r in rated), default=float("nan"))
    print("train_stage1: %s, %d steps in %.0f s (%.0f steps/s): goal rate %.2f first window, "
          "%.2f last, %.2f best; %s%s"
          % (args.algo.upper(), log.steps, wall, log.steps / max(wall, 1e-9), first, last, best,
             csv_path, (", " + plot_path) if drew else " (no plot: matplotlib missing)"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
