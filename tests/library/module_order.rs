//! The library's modules depend on each other in the order src/lib.rs's doc comment lists them:
//! every top-level module is linked there (`[`name`]` or `[`name::Thing`]`), and each one's files
//! (src/NAME.rs and src/NAME/**.rs) use, through `crate::` paths or `super::` paths that climb to
//! the crate, only the modules linked before it. Unit tests (`#[cfg(test)]` items, and the files
//! of `#[cfg(test)] mod`s) may use anything; so may comments, doc links included.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use crate::rust_source::{
    Token, code_only, is, is_ident, read, rust_files_under, src, tokens, without_tests,
};

/// The modules src/lib.rs declares, each with whether it is `pub`.
fn declared_modules(lib: &str) -> BTreeMap<String, bool> {
    let tokens = tokens(&code_only(lib));
    let mut modules = BTreeMap::new();
    for (i, window) in tokens.windows(3).enumerate() {
        if window[0].text == "mod" && is_ident(&window[1].text) && window[2].text == ";" {
            let public = i > 0 && tokens[i - 1].text == "pub";
            modules.insert(window[1].text.clone(), public);
        }
    }
    modules
}

/// The modules in the order the doc comment of src/lib.rs first links them.
fn doc_order(lib: &str, modules: &BTreeMap<String, bool>) -> Vec<String> {
    let doc: String = lib
        .lines()
        .filter_map(|line| line.trim_start().strip_prefix("//!"))
        .collect::<Vec<_>>()
        .join("\n");
    let mut order: Vec<String> = Vec::new();
    for link in doc.split("[`").skip(1) {
        let Some((target, _)) = link.split_once('`') else {
            continue;
        };
        let target = target.strip_prefix("crate::").unwrap_or(target);
        let name = target.split("::").next().unwrap_or(target);
        if modules.contains_key(name) && !order.iter().any(|m| m == name) {
            order.push(name.to_string());
        }
    }
    order
}

/// The first names of the paths at `tokens[i..]`: `name` or a group `{a::b, c}`.
fn path_heads(tokens: &[Token], i: usize) -> Vec<&Token> {
    let Some(first) = tokens.get(i) else {
        return Vec::new();
    };
    if first.text != "{" {
        return vec![first];
    }
    let (mut heads, mut depth, mut expect) = (Vec::new(), 0, true);
    for token in &tokens[i..] {
        match token.text.as_str() {
            "{" => depth += 1,
            "}" => depth -= 1,
            "," if depth == 1 => {
                expect = true;
                continue;
            }
            text if depth == 1 && expect && is_ident(text) => heads.push(token),
            _ => {}
        }
        if depth == 0 {
            break;
        }
        expect = expect && token.text == "{";
    }
    heads
}

/// The top-level modules `code` names (with the line of each mention): `crate::NAME`,
/// `crate::{NAME, …}`, and `super::…::NAME` where the `super`s climb from the file's module
/// (`depth` names below the crate) to the crate.
fn modules_used(tokens: &[Token], depth: usize) -> Vec<(String, usize)> {
    let mut used = Vec::new();
    let (mut braces, mut inline_modules) = (0, Vec::new());
    for (i, token) in tokens.iter().enumerate() {
        let after_path = i > 0 && tokens[i - 1].text == "::";
        let heads_at = match token.text.as_str() {
            "{" => {
                braces += 1;
                if i >= 2 && tokens[i - 2].text == "mod" {
                    inline_modules.push(braces);
                }
                None
            }
            "}" => {
                if inline_modules.last() == Some(&braces) {
                    inline_modules.pop();
                }
                braces -= 1;
                None
            }
            "crate" if !after_path && is(tokens, i + 1, &["::"]) => Some(i + 2),
            "super" if !after_path => {
                let mut k = i;
                while is(tokens, k, &["super", "::"]) {
                    k += 2;
                }
                ((k - i) / 2 == depth + inline_modules.len()).then_some(k)
            }
            _ => None,
        };
        if let Some(at) = heads_at {
            used.extend(
                path_heads(tokens, at)
                    .into_iter()
                    .map(|head| (head.text.clone(), head.line)),
            );
        }
    }
    used
}

/// The `.rs` files of module `name`, each with its depth below the crate: src/NAME.rs and
/// everything under src/NAME/, less the files of `#[cfg(test)]` modules.
fn module_files(src: &Path, name: &str) -> Vec<(PathBuf, usize)> {
    let mut files = Vec::new();
    let file = src.join(format!("{name}.rs"));
    if file.is_file() {
        files.push(file);
    }
    files.extend(rust_files_under(&src.join(name)));
    files
        .into_iter()
        .map(|path| {
            let parts = path.strip_prefix(src).unwrap().components().count();
            let depth = if path.ends_with("mod.rs") {
                parts - 1
            } else {
                parts
            };
            (path, depth)
        })
        .collect()
}

/// The directory of the modules a file declares: src/a/b for src/a/b.rs and src/a/b/mod.rs.
fn children_dir(file: &Path) -> PathBuf {
    if file.ends_with("mod.rs") {
        file.parent().unwrap().to_path_buf()
    } else {
        file.with_extension("")
    }
}

#[test]
fn every_public_module_is_linked_in_the_doc_comment() {
    let lib = read(&src().join("lib.rs"));
    let modules = declared_modules(&lib);
    assert!(modules.len() > 10, "src/lib.rs declares {modules:?}");
    let order = doc_order(&lib, &modules);
    let missing: Vec<String> = modules
        .iter()
        .filter(|&(name, &public)| public && !order.contains(name))
        .map(|(name, _)| {
            format!("src/lib.rs declares `pub mod {name}` but its doc comment never links it")
        })
        .collect();
    assert!(
        missing.is_empty(),
        "{}\n(link each module, as [`name`] or [`name::Thing`], where it belongs in the \
         dependency order: after every module it uses)",
        missing.join("\n")
    );
}

#[test]
fn each_module_uses_only_the_modules_linked_before_it() {
    let src = src();
    let lib = read(&src.join("lib.rs"));
    let modules = declared_modules(&lib);
    let order = doc_order(&lib, &modules);
    let position = |name: &str| order.iter().position(|m| m == name);
    let mut problems = Vec::new();
    let mut checked = 0;
    for (index, name) in order.iter().enumerate() {
        let files = module_files(&src, name);
        assert!(
            !files.is_empty(),
            "module `{name}` has no src/{name}.rs nor src/{name}/"
        );
        let files: Vec<_> = files
            .into_iter()
            .filter_map(|(file, depth)| {
                let (tokens, test_modules) = without_tests(tokens(&code_only(&read(&file))))?;
                Some((file, depth, tokens, test_modules))
            })
            .collect();
        let test_code: Vec<PathBuf> = files
            .iter()
            .flat_map(|(file, _, _, test_modules)| {
                let dir = children_dir(file);
                test_modules
                    .iter()
                    .flat_map(move |m| [dir.join(format!("{m}.rs")), dir.join(m)])
            })
            .collect();
        for (file, depth, tokens, _) in &files {
            if test_code.iter().any(|test| file.starts_with(test)) {
                continue;
            }
            checked += 1;
            let shown = file.strip_prefix(src.parent().unwrap()).unwrap().display();
            let mut seen = BTreeSet::new();
            for (used, line) in modules_used(tokens, *depth) {
                if used == *name || !modules.contains_key(&used) || !seen.insert(used.clone()) {
                    continue;
                }
                match position(&used) {
                    Some(at) if at < index => {}
                    Some(_) => problems.push(format!(
                        "{shown}:{line}: module `{name}` uses `{used}`, which src/lib.rs's doc \
                         comment links after `{name}`"
                    )),
                    None => problems.push(format!(
                        "{shown}:{line}: module `{name}` uses `{used}`, which src/lib.rs's doc \
                         comment never links"
                    )),
                }
            }
        }
    }
    assert!(checked > order.len(), "only {checked} files checked");
    assert!(
        problems.is_empty(),
        "{}\n(reorder src/lib.rs's doc comment so that each module comes after the modules it \
         uses, or drop the dependency)",
        problems.join("\n")
    );
}

/// The names `modules_used` finds in a file's text.
fn used_in(text: &str, depth: usize) -> Vec<String> {
    let (tokens, _) = without_tests(tokens(&code_only(text))).unwrap_or_default();
    modules_used(&tokens, depth)
        .into_iter()
        .map(|(name, _)| name)
        .collect()
}

#[test]
fn paths_are_found_alone_in_groups_and_through_super() {
    let text = "use crate::color::Color;\n\
                use crate::{aabb::Aabb, ray::{Ray, Hit}, tone};\n\
                fn f() -> crate::film::Film { $crate::stats::count() }\n\
                pub(crate) use super::super::light::Light;\n\
                use super::Sibling;\n\
                mod inner { use super::super::super::medium::Fog; }";
    assert_eq!(
        used_in(text, 2),
        [
            "color", "aabb", "ray", "tone", "film", "stats", "light", "medium"
        ]
    );
    let lines: Vec<usize> = modules_used(&tokens(&code_only(text)), 2)
        .into_iter()
        .map(|(_, line)| line)
        .collect();
    assert_eq!(lines, [1, 2, 2, 2, 3, 3, 4, 6]);
}

#[test]
fn comments_literals_and_test_code_are_left_out() {
    let text = r####"
        // use crate::a;
        /* crate::b /* nested */ crate::c */
        /// [`crate::d`]
        const S: &str = "crate::e \" crate::f";
        const R: &str = r#"crate::g " crate::h"#;
        const C: [char; 3] = ['"', '\'', '{'];
        fn life<'a>(x: &'a str) -> &'a str { x }
        #[cfg(test)]
        use crate::i;
        struct S { #[cfg(test)] field: crate::j::J, other: crate::kept::K }
        #[cfg(test)]
        #[allow(unused)]
        mod tests { use crate::k; fn f() { let _ = "}"; } }
        #[cfg(test)]
        mod test_support;
        use crate::also_kept;
    "####;
    assert_eq!(used_in(text, 1), ["kept", "also_kept"]);
    let (_, test_modules) = without_tests(tokens(&code_only(text))).unwrap();
    assert_eq!(test_modules, ["test_support"]);
    assert_eq!(
        without_tests(tokens("#![cfg(test)] use crate::x;")).map(|_| ()),
        None
    );
}

#[test]
fn the_doc_comment_order_is_that_of_first_links() {
    let lib = "//! Basics: [`b`] and [`a::Thing`], then [`crate::c`], [`a`] again, [`Other`].\n\
               //! [`d`] waits.\n\
               pub mod a;\npub mod b;\npub(crate) mod c;\nmod d;\n";
    let modules = declared_modules(lib);
    let public: Vec<(&str, bool)> = modules.iter().map(|(m, &p)| (m.as_str(), p)).collect();
    assert_eq!(
        public,
        [("a", true), ("b", true), ("c", false), ("d", false)]
    );
    assert_eq!(doc_order(lib, &modules), ["b", "a", "c", "d"]);
}
