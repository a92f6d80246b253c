//! The OPC UA server's users (`--opcua-users FILE`): a TOML file with a `[users]` table of
//! names and passwords. With users, anonymous clients are refused.
//!
//! ```toml
//! [users]
//! operator = "secret"
//! ```

use std::collections::BTreeMap;
use std::path::Path;

use miette::Diagnostic;
use serde::Deserialize;
use thiserror::Error;

#[derive(Debug, Error, Diagnostic)]
#[error("cannot take the OPC UA users from {path}: {reason}")]
#[diagnostic(
    code(awl::serve::opcua_users),
    help(
        "write a TOML file with a table of names and passwords: `[users]` then `operator = \"secret\"`"
    )
)]
pub struct UsersError {
    path: String,
    reason: String,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct UsersFile {
    users: BTreeMap<String, String>,
}

/// The users and passwords of `path`, in name order; at least one.
pub fn read(path: &Path) -> Result<Vec<(String, String)>, UsersError> {
    let failed = |reason: String| UsersError {
        path: path.display().to_string(),
        reason,
    };
    let text = std::fs::read_to_string(path).map_err(|error| failed(error.to_string()))?;
    let file: UsersFile =
        toml::from_str(&text).map_err(|error| failed(error.message().to_string()))?;
    if file.users.is_empty() {
        return Err(failed("it names no user".to_string()));
    }
    if let Some((name, _)) = file.users.iter().find(|(_, password)| password.is_empty()) {
        return Err(failed(format!("user `{name}` has an empty password")));
    }
    Ok(file.users.into_iter().collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read_text(text: &str) -> Result<Vec<(String, String)>, UsersError> {
        let path = std::env::temp_dir().join(format!("awl-users-{}.toml", std::process::id()));
        std::fs::write(&path, text).unwrap();
        let users = read(&path);
        let _ = std::fs::remove_file(&path);
        users
    }

    #[test]
    fn users_are_a_table_of_names_and_passwords() {
        let users = read_text("[users]\noperator = \"secret\"\nadmin = \"x\"\n").unwrap();
        assert_eq!(users[1], ("operator".to_string(), "secret".to_string()));
    }

    #[test]
    fn a_file_without_users_or_with_an_empty_password_is_refused() {
        assert!(
            read_text("[users]\n")
                .unwrap_err()
                .to_string()
                .contains("no user")
        );
        let empty = read_text("[users]\nop = \"\"\n").unwrap_err();
        assert!(empty.to_string().contains("empty password"), "{empty}");
        assert!(read_text("users = 3").is_err());
        assert!(read(Path::new("/no/such/users.toml")).is_err());
    }
}
