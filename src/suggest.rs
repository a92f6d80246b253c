//! The names a help offers for one written wrong ("did you mean `run`?"): the closest of the
//! names that would do, when it is close enough to be a typo.

/// The closest of `candidates` to `word`: at most two edits away, and fewer edits than the
/// candidate has letters (a key of a scenario, a help topic, a debugger command).
pub fn did_you_mean<'a>(word: &str, candidates: impl Iterator<Item = &'a str>) -> Option<&'a str> {
    candidates
        .map(|candidate| (strsim::damerau_levenshtein(word, candidate), candidate))
        .filter(|(distance, candidate)| *distance <= 2 && *distance < candidate.len())
        .min_by_key(|(distance, _)| *distance)
        .map(|(_, candidate)| candidate)
}

/// The name of `names` one edit from `written`, case aside: what a typo of a jump label, a
/// parameter, a variable or a data block's value most likely meant.
pub fn one_edit_from<'a>(
    written: &str,
    names: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    let written = written.to_ascii_uppercase();
    names
        .into_iter()
        .map(|name| {
            let distance = strsim::damerau_levenshtein(&written, &name.to_ascii_uppercase());
            (distance, name)
        })
        .filter(|(distance, _)| *distance <= 1)
        .min_by_key(|(distance, _)| *distance)
        .map(|(_, name)| name)
}
