"""Learn a behaviour tree from demonstrations (by default the model-based learner the session
uses) or with one of the thesis's three approaches (§4.1-4.3).

Example:
    teach learn demos/ball/delta4 --prune -o delta4.xml
    teach learn demos/ball/delta1 --approach specialize --prune -o delta1.xml

Approaches:
  model       (default) an action model and a goal learned from the transitions, a reactive tree
              planned from them by backchaining and repaired until it reproduces every
              demonstration; repeated steps, other orders and loops are fine
  pabt        PA-BT from the domain's own action model and goal (no demonstrations needed;
              DEMO_DIR may be a domain.toml or a folder holding one)
  detect      PA-BT on the preconditions, ramifications and goal detected in the demonstrations
  specialize  the demonstrated action order, then the over-general tree specialized on every
              demonstration

--generations DIR writes every generation as DIR/gen-NN.xml (for specialize: the tree after
each demonstration that changed it; with --prune the pruned tree comes last). The summary line
gives the node counts and how many training demonstrations the written tree reproduces.
"""

from __future__ import annotations

import argparse
import importlib.util
from pathlib import Path

NAME = "learn"
HELP = "learn a behaviour tree from demonstrations or an action model"
ORDER = 15


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("source", type=Path, metavar="DEMO_DIR",
                        help="folder of CSV demonstrations (pabt: a domain.toml or a folder with one)")
    parser.add_argument("--approach", choices=("safe", "model", "pabt", "detect", "specialize"),
                        default="safe", help="which learner (default: safe, which never acts on a guess; model: "
                                             "the same learner guessing, for comparison)")
    parser.add_argument("--prune", action="store_true", help="remove redundant nodes (Alg. 4.1-4.4)")
    parser.add_argument("--domain", type=Path, help="domain.toml (default: in the folder or its parent)")
    parser.add_argument("--goal", nargs="+", metavar="LIT",
                        help="pabt: goal literals instead of the domain's, e.g. BallPlaced or !BallGrasped")
    parser.add_argument("-o", "--output", type=Path, required=True, help="where to write the tree")
    parser.add_argument("--generations", type=Path, metavar="DIR", help="write every generation as gen-NN.xml")


def outputs(args: argparse.Namespace) -> list[tuple[str, Path]]:
    """What this command writes, checked and locked before it runs (teach.lock.claim_outputs)."""
    return [("file", args.output)] + ([("folder", args.generations)] if args.generations else [])


def inputs(args: argparse.Namespace) -> list[tuple[str, Path]]:
    """What this command reads, which no output may replace (teach.protect): the set whole."""
    source = ("domain file" if args.approach == "pabt" and args.source.is_file() else "set", args.source)
    return [source] + ([("domain file", args.domain)] if args.domain else [])


def run(args: argparse.Namespace) -> int:
    from teach.bt.nodes import size
    from teach.bt.xml import write_tree
    from teach.domain import Literal
    from teach.errors import LearnError
    from teach.generations import write_generations
    from teach.replay import replay

    domain, demos = _inputs(args)
    if args.goal and args.approach != "pabt":
        raise LearnError("--goal is for --approach pabt; the other approaches detect the goal in the demonstrations")
    goal = [Literal.parse(text) for text in args.goal] if args.goal else None
    for literal in goal or ():
        domain.index(literal.name)
    generations, ramifications = _learn(args.approach, domain, demos, goal)
    tree = generations[-1]
    parts = [f"{args.approach}: {size(tree)} nodes"]
    if args.prune:
        if importlib.util.find_spec("teach.learn.prune") is None:
            raise LearnError("--prune needs teach.learn.prune, which this installation does not have")
        from teach.learn.prune import prune

        tree = prune(tree, ramifications)
        generations = [*generations, tree]
        parts.append(f"{size(tree)} after pruning")
    write_tree(args.output, tree)  # both outputs were checked before learning (see outputs)
    if args.generations:
        write_generations(args.generations, generations)
        parts.append(f"{len(generations)} generations in {args.generations}")
    if demos:
        parts.append(f"training set {replay(tree, domain, demos).summary()} (strict)")
    print(", ".join(parts) + f" -> {args.output}")
    return 0


def _inputs(args: argparse.Namespace):  # type: ignore[no-untyped-def]
    """The domain and (for the learners that use them) the demonstrations."""
    from teach.demos import read_demo_set
    from teach.domain import find_domain_file, load_domain
    from teach.errors import FormatError

    source: Path = args.source
    if not source.exists():  # "delta22" was learned (pabt: from the domain file of the folder above)
        raise FormatError("no such file or folder", source)
    domain = load_domain(args.domain) if args.domain else None
    if args.approach == "pabt":
        if domain is None:
            domain = load_domain(source if source.is_file() else find_domain_file(source))
        has_demos = source.is_dir() and any(source.glob("*.csv"))
        return domain, (read_demo_set(source, domain)[1] if has_demos else [])
    if not source.is_dir():
        raise FormatError(f"--approach {args.approach} needs a folder of CSV demonstrations", source)
    return read_demo_set(source, domain)


def _learn(approach: str, domain, demos, goal):  # type: ignore[no-untyped-def]
    """Generations (last = the learned tree) and the ramifications pruning may use."""
    from teach.errors import LearnError
    from teach.learn.model import detect_model, learn_detect
    from teach.learn.order import action_order
    from teach.learn.pabt import expand
    from teach.learn.prune import ramifications_of
    from teach.learn.specialize import Specializer

    if approach == "pabt":
        return expand(domain, goal), {a.name: a.ram for a in domain.actions if a.ram}
    model = detect_model(domain, demos)
    ramifications = {a.name: a.ram for a in model.actions if a.ram}
    if approach == "detect":
        return learn_detect(domain, demos), ramifications
    if not any(demo.actions for demo in demos):
        raise LearnError("no demonstration shows an action (only goal states), so there is no behaviour to learn",
                         demos[0].path.parent if demos and demos[0].path else None)
    if approach in ("model", "safe"):
        from teach.learn.learner import learn_online

        model_learner = learn_online(domain, [], safe=approach == "safe")
        model_generations = [model_learner.tree]
        for demo in demos:
            if model_learner.update(demo).changed:
                model_generations.append(model_learner.tree)
        return model_generations, ramifications_of(model)
    learner = Specializer(domain, action_order(domain, demos))
    generations = [learner.tree]
    for demo in demos:
        if learner.update(demo).changed:
            generations.append(learner.tree)
    return generations, ramifications
