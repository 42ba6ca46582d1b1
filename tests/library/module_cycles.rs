//! Each folder's files and subfolders depend on each other one way only. In every module of the
//! library and of the `raylab` binary, the modules it declares (a file `X.rs` or a folder `X/`)
//! are its rooms; a room uses another through a path (`crate::…`, `super::…`, `self::…`,
//! `use` groups included), and no room may reach itself back through such uses. The module's
//! own file (`lib.rs`, `main.rs`, `mod.rs`) declares the rooms and is none of them. Test code
//! (`#[cfg(test)]` items and modules) may use anything.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use crate::rust_source::{Token, code_only, is, is_ident, read, src, tokens, without_tests};

/// A file of a crate, as the test reads it.
struct SourceFile {
    path: PathBuf,
    /// Its module's path from the crate's root: `["cli", "bench"]` for src/cli/bench.rs.
    module: Vec<String>,
    tokens: Vec<Token>,
}

/// A use of room `to` by room `from`, both declared by the same module, at `file:line`.
#[derive(Clone, Debug)]
struct Use {
    from: String,
    to: String,
    at: String,
}

/// The files of the crate whose root is `root`, less test code, and the rooms each module
/// declares (by the module's path).
fn crate_files(root: &Path) -> (Vec<SourceFile>, BTreeMap<Vec<String>, BTreeSet<String>>) {
    let (mut files, mut rooms) = (Vec::new(), BTreeMap::new());
    let mut todo = vec![(root.to_path_buf(), Vec::new())];
    while let Some((path, module)) = todo.pop() {
        let Some((tokens, _)) = without_tests(tokens(&code_only(&read(&path)))) else {
            continue;
        };
        let dir = if module.is_empty() || path.ends_with("mod.rs") {
            path.parent().unwrap().to_path_buf()
        } else {
            path.with_extension("")
        };
        let declared: BTreeSet<String> = tokens
            .windows(3)
            .filter(|w| w[0].text == "mod" && is_ident(&w[1].text) && w[2].text == ";")
            .map(|w| w[1].text.clone())
            .collect();
        for name in &declared {
            let file = dir.join(format!("{name}.rs"));
            let child = if file.is_file() {
                file
            } else {
                dir.join(name).join("mod.rs")
            };
            let mut child_module = module.clone();
            child_module.push(name.clone());
            todo.push((child, child_module));
        }
        rooms.insert(module.clone(), declared);
        files.push(SourceFile {
            path,
            module,
            tokens,
        });
    }
    (files, rooms)
}

/// Every path that starts at `tokens[i]`, one per name a `{…}` group lists: `a::b` gives
/// `[a, b]`, `a::{b, c::d, self}` gives `[a, b]`, `[a, c, d]` and `[a]`.
fn expand(tokens: &[Token], i: usize) -> Vec<Vec<String>> {
    let Some(first) = tokens.get(i) else {
        return vec![Vec::new()];
    };
    if first.text == "{" {
        let (mut paths, mut depth, mut k) = (Vec::new(), 0, i);
        let mut item_starts = vec![i + 1];
        while k < tokens.len() {
            match tokens[k].text.as_str() {
                "{" => depth += 1,
                "}" => depth -= 1,
                "," if depth == 1 => item_starts.push(k + 1),
                _ => {}
            }
            if depth == 0 {
                break;
            }
            k += 1;
        }
        for start in item_starts {
            if tokens.get(start).is_some_and(|t| t.text != "}") {
                paths.extend(expand(tokens, start));
            }
        }
        return paths;
    }
    if first.text == "self" || !is_ident(&first.text) {
        return vec![Vec::new()];
    }
    let rest = if is(tokens, i + 1, &["::"]) {
        expand(tokens, i + 2)
    } else {
        vec![Vec::new()]
    };
    rest.into_iter()
        .map(|mut tail| {
            tail.insert(0, first.text.clone());
            tail
        })
        .collect()
}

/// The crate paths a file's code names, each with its line: `crate::a::b`, `super::c`,
/// `self::d`, resolved from the file's module.
fn paths_named(file: &SourceFile) -> Vec<(Vec<String>, usize)> {
    let tokens = &file.tokens;
    let mut named = Vec::new();
    for (i, token) in tokens.iter().enumerate() {
        if i > 0 && tokens[i - 1].text == "::" {
            continue;
        }
        let (base, at): (&[String], usize) = match token.text.as_str() {
            "crate" if is(tokens, i + 1, &["::"]) => (&[], i + 2),
            "self" if is(tokens, i + 1, &["::"]) => (&file.module, i + 2),
            "super" => {
                let mut k = i;
                while is(tokens, k, &["super", "::"]) {
                    k += 2;
                }
                let ups = (k - i) / 2;
                if ups == 0 || ups > file.module.len() {
                    continue;
                }
                (&file.module[..file.module.len() - ups], k)
            }
            _ => continue,
        };
        for tail in expand(tokens, at) {
            let mut path = base.to_vec();
            path.extend(tail);
            named.push((path, token.line));
        }
    }
    named
}

/// The uses between rooms in the crate at `root`, by the module that declares the rooms.
fn uses_between_rooms(root: &Path) -> BTreeMap<Vec<String>, Vec<Use>> {
    let (files, rooms) = crate_files(root);
    let project = src().parent().unwrap().to_path_buf();
    let mut uses: BTreeMap<Vec<String>, Vec<Use>> = BTreeMap::new();
    for file in &files {
        let shown = file.path.strip_prefix(&project).unwrap().display();
        for (path, line) in paths_named(file) {
            for level in 0..file.module.len() {
                let (owner, from) = (&file.module[..level], &file.module[level]);
                let Some(to) = path.get(level) else { continue };
                if path[..level] == *owner && to != from && rooms[owner].contains(to) {
                    uses.entry(owner.to_vec()).or_default().push(Use {
                        from: from.clone(),
                        to: to.clone(),
                        at: format!("{shown}:{line}"),
                    });
                }
            }
        }
    }
    uses
}

/// The sets of two or more rooms that reach each other through `uses` (Tarjan's strongly
/// connected components).
fn cycles(uses: &[Use]) -> Vec<BTreeSet<String>> {
    let mut next: BTreeMap<&str, BTreeSet<&str>> = BTreeMap::new();
    for u in uses {
        next.entry(&u.from).or_default().insert(&u.to);
        next.entry(&u.to).or_default();
    }
    struct Walk<'a> {
        next: &'a BTreeMap<&'a str, BTreeSet<&'a str>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        found: Vec<BTreeSet<String>>,
    }
    fn visit<'a>(walk: &mut Walk<'a>, v: &'a str) {
        let n = walk.index.len();
        walk.index.insert(v, n);
        walk.low.insert(v, n);
        walk.stack.push(v);
        for &w in &walk.next[v] {
            if !walk.index.contains_key(w) {
                visit(walk, w);
                walk.low.insert(v, walk.low[v].min(walk.low[w]));
            } else if walk.stack.contains(&w) {
                walk.low.insert(v, walk.low[v].min(walk.index[w]));
            }
        }
        if walk.low[v] == walk.index[v] {
            let at = walk.stack.iter().rposition(|&w| w == v).unwrap();
            let component: BTreeSet<String> = walk.stack.drain(at..).map(str::to_string).collect();
            if component.len() > 1 {
                walk.found.push(component);
            }
        }
    }
    let mut walk = Walk {
        next: &next,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        found: Vec::new(),
    };
    for &v in next.keys() {
        if !walk.index.contains_key(v) {
            visit(&mut walk, v);
        }
    }
    walk.found
}

#[test]
fn the_rooms_of_every_module_depend_on_each_other_one_way() {
    let mut problems = Vec::new();
    let mut checked = 0;
    for root in ["lib.rs", "main.rs"] {
        for (owner, uses) in uses_between_rooms(&src().join(root)) {
            checked += uses.len();
            for cycle in cycles(&uses) {
                let within: Vec<String> = uses
                    .iter()
                    .filter(|u| cycle.contains(&u.from) && cycle.contains(&u.to))
                    .map(|u| format!("  {} uses {} at {}", u.from, u.to, u.at))
                    .collect::<BTreeSet<_>>()
                    .into_iter()
                    .collect();
                problems.push(format!(
                    "in `{}` of {root}, {} use each other:\n{}",
                    owner.join("::"),
                    cycle.into_iter().collect::<Vec<_>>().join(", "),
                    within.join("\n")
                ));
            }
        }
    }
    assert!(checked > 100, "only {checked} uses between rooms found");
    assert!(
        problems.is_empty(),
        "{}\n(move what both need into one of them, or into a room both use)",
        problems.join("\n")
    );
}

#[test]
fn paths_are_resolved_through_groups_super_and_self() {
    let file = SourceFile {
        path: PathBuf::from("src/a/b.rs"),
        module: vec!["a".into(), "b".into()],
        tokens: tokens(&code_only(
            "use crate::{x::{y, z::w}, v};\n\
             use super::c::{self, d};\n\
             fn f() { self::inner::g(); super::super::top::h(); $crate::m::n!(); }",
        )),
    };
    let named: Vec<(String, usize)> = paths_named(&file)
        .into_iter()
        .map(|(path, line)| (path.join("::"), line))
        .collect();
    let expected = [
        ("x::y", 1),
        ("x::z::w", 1),
        ("v", 1),
        ("a::c", 2),
        ("a::c::d", 2),
        ("a::b::inner::g", 3),
        ("top::h", 3),
        ("m::n", 3),
    ];
    let expected: Vec<(String, usize)> =
        expected.iter().map(|&(p, l)| (p.to_string(), l)).collect();
    assert_eq!(named, expected);
}

#[test]
fn a_cycle_through_three_rooms_is_found_and_a_chain_is_not() {
    let use_of = |from: &str, to: &str| Use {
        from: from.into(),
        to: to.into(),
        at: String::new(),
    };
    let chain = [use_of("a", "b"), use_of("b", "c"), use_of("a", "c")];
    assert!(cycles(&chain).is_empty());
    let circle = [
        use_of("a", "b"),
        use_of("b", "c"),
        use_of("c", "a"),
        use_of("c", "d"),
    ];
    let found = cycles(&circle);
    assert_eq!(found.len(), 1);
    assert_eq!(found[0], ["a", "b", "c"].map(String::from).into());
}
