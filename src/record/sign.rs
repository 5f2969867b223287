//! Lecturers' keys: `rattleback keygen NAME` writes `NAME.key` (the private key, mode 0600) and
//! `NAME.pub`; `--sign NAME.key` signs a recording's end line; `replay --verify --key NAME.pub`
//! checks the signature. ed25519 (`ed25519-dalek`); the signed message is the chain value before
//! the end line (a SHA-256 that commits to every byte before it) with the line count and the
//! signer's name and key, so neither a line nor the end record can change without the signature
//! failing.

use std::path::Path;

use ed25519_dalek::{Signature, Signer as _, SigningKey, VerifyingKey};
use serde::{Deserialize, Serialize};

/// A key file's contents (private or public), TOML.
#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct KeyFile {
    /// What the file is.
    kind: String,
    /// The lecturer's name, shown as "signed by NAME".
    name: String,
    /// The key, hex (32 bytes).
    key: String,
}

const SECRET_KIND: &str = "rattleback ed25519 private key";
const PUBLIC_KIND: &str = "rattleback ed25519 public key";

/// A private key and its name.
pub struct Signer {
    /// The name it signs as.
    pub name: String,
    key: SigningKey,
}

/// A public key and its name.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PublicKey {
    /// The name it was made for.
    pub name: String,
    key: VerifyingKey,
}

/// Problems with keys.
#[derive(Debug, thiserror::Error)]
pub enum KeyError {
    /// Cannot read or write a key file.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// What the system said.
        source: std::io::Error,
    },
    /// Not a key file of the kind expected.
    #[error("{path}: {message}")]
    Bad {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
}

fn bad(path: &Path, message: impl Into<String>) -> KeyError {
    KeyError::Bad {
        path: path.display().to_string(),
        message: message.into(),
    }
}

fn read_key(path: &Path, kind: &str) -> Result<(String, [u8; 32]), KeyError> {
    let text = crate::scenario::write::read_bounded(path, 4096).map_err(|source| KeyError::Io {
        path: path.display().to_string(),
        source,
    })?;
    let file: KeyFile = toml::from_str(&text).map_err(|e| {
        bad(
            path,
            format!("not a rattleback key file ({})", e.message().trim()),
        )
    })?;
    if file.kind != kind {
        return Err(bad(
            path,
            format!("this is a '{}', expected a '{kind}'", file.kind),
        ));
    }
    let bytes: [u8; 32] = hex::decode(file.key.trim())
        .ok()
        .and_then(|b| b.try_into().ok())
        .ok_or_else(|| bad(path, "key: expected 64 hexadecimal digits"))?;
    Ok((crate::scenario::text::clean(&file.name), bytes))
}

impl Signer {
    /// Reads a private key file.
    ///
    /// # Errors
    /// Unreadable, not a private key file, or a malformed key.
    pub fn read(path: &Path) -> Result<Self, KeyError> {
        let (name, bytes) = read_key(path, SECRET_KIND)?;
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt as _;
            if let Ok(meta) = std::fs::metadata(path)
                && meta.permissions().mode() & 0o077 != 0
            {
                // Refused, as ssh refuses such a key: a warning would vanish behind the
                // explorer's screen (issue 56).
                return Err(bad(
                    path,
                    format!(
                        "the private key can be read by others (mode {:o}); make it yours alone with `chmod 600` and try again",
                        meta.permissions().mode() & 0o777
                    ),
                ));
            }
        }
        Ok(Self {
            name,
            key: SigningKey::from_bytes(&bytes),
        })
    }

    /// The public half.
    #[must_use]
    pub fn public(&self) -> PublicKey {
        PublicKey {
            name: self.name.clone(),
            key: self.key.verifying_key(),
        }
    }

    /// The signature of `message`, hex.
    #[must_use]
    pub fn sign(&self, message: &[u8]) -> String {
        hex::encode(self.key.sign(message).to_bytes())
    }
}

impl PublicKey {
    /// Reads a public key file.
    ///
    /// # Errors
    /// Unreadable, not a public key file, or a malformed key.
    pub fn read(path: &Path) -> Result<Self, KeyError> {
        let (name, bytes) = read_key(path, PUBLIC_KIND)?;
        let key = VerifyingKey::from_bytes(&bytes)
            .map_err(|_| bad(path, "key: not a valid ed25519 public key"))?;
        Ok(Self { name, key })
    }

    /// The key as a session's end line writes it (hex).
    #[must_use]
    pub fn hex(&self) -> String {
        hex::encode(self.key.to_bytes())
    }

    /// A short fingerprint: the first 16 hex digits of the key's SHA-256.
    #[must_use]
    pub fn fingerprint(&self) -> String {
        fingerprint(&self.hex())
    }
}

/// The fingerprint of a hex public key (the first 16 hex digits of its SHA-256).
#[must_use]
pub fn fingerprint(public_hex: &str) -> String {
    use sha2::Digest as _;
    hex::encode(sha2::Sha256::digest(public_hex.as_bytes()))[..16].to_owned()
}

/// The message an end line's signature covers.
#[must_use]
pub fn message(chain: &str, lines: usize, signer: &str, public_hex: &str) -> Vec<u8> {
    format!("rattleback-session-signature\n{chain}\n{lines}\n{signer}\n{public_hex}").into_bytes()
}

/// Whether `signature` (hex) is `public_hex`'s signature of `message`.
#[must_use]
pub fn check(public_hex: &str, message: &[u8], signature: &str) -> bool {
    let Some(key) = hex::decode(public_hex)
        .ok()
        .and_then(|b| <[u8; 32]>::try_from(b).ok())
        .and_then(|b| VerifyingKey::from_bytes(&b).ok())
    else {
        return false;
    };
    let Some(sig) = hex::decode(signature)
        .ok()
        .and_then(|b| <[u8; 64]>::try_from(b).ok())
        .map(|b| Signature::from_bytes(&b))
    else {
        return false;
    };
    key.verify_strict(message, &sig).is_ok()
}

/// Writes `NAME.key` (mode 0600, never replacing a file) and `NAME.pub` for a new key; returns
/// both paths.
///
/// # Errors
/// A file exists, cannot be written, or the system has no randomness.
#[cfg(not(target_arch = "wasm32"))]
pub fn keygen(stem: &Path) -> Result<(std::path::PathBuf, std::path::PathBuf), KeyError> {
    let name = stem
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .filter(|n| !n.is_empty())
        .ok_or_else(|| bad(stem, "give a name for the key files, such as 'lecturer'"))?;
    // A name is shown and typed: no control, bidirectional or separator character (a name with
    // an escape sequence was printed as another file's, issue 56).
    if !crate::scenario::text::is_plain(&name) {
        return Err(bad(
            Path::new(&crate::scenario::text::visible(&stem.display().to_string())),
            "a key's name cannot have control or invisible characters (a newline, an escape); choose letters, digits, - or _",
        ));
    }
    let secret_path = stem.with_file_name(format!("{name}.key"));
    let public_path = stem.with_file_name(format!("{name}.pub"));
    let mut seed = [0u8; 32];
    getrandom::fill(&mut seed).map_err(|e| KeyError::Io {
        path: secret_path.display().to_string(),
        source: std::io::Error::other(format!("no randomness from the system: {e}")),
    })?;
    let key = SigningKey::from_bytes(&seed);
    let toml_of = |kind: &str, key: String| {
        toml::to_string(&KeyFile {
            kind: kind.to_owned(),
            name: name.clone(),
            key,
        })
        .unwrap_or_default()
    };
    let secret = toml_of(SECRET_KIND, hex::encode(key.to_bytes()));
    let public = toml_of(PUBLIC_KIND, hex::encode(key.verifying_key().to_bytes()));
    if public_path.exists() {
        return Err(KeyError::Io {
            path: public_path.display().to_string(),
            source: std::io::Error::new(
                std::io::ErrorKind::AlreadyExists,
                "exists; choose another name (nothing was overwritten)",
            ),
        });
    }
    write_new(&secret_path, secret.as_bytes(), true)?;
    if let Err(e) = write_new(&public_path, public.as_bytes(), false) {
        let _ = std::fs::remove_file(&secret_path);
        return Err(e);
    }
    Ok((secret_path, public_path))
}

/// Creates `path` (never replacing a file), private (0600) when asked.
#[cfg(not(target_arch = "wasm32"))]
fn write_new(path: &Path, bytes: &[u8], private: bool) -> Result<(), KeyError> {
    use std::io::Write as _;
    let io = |source: std::io::Error| {
        let source = if source.kind() == std::io::ErrorKind::AlreadyExists {
            std::io::Error::new(
                source.kind(),
                "exists; choose another name (nothing was overwritten)",
            )
        } else {
            source
        };
        KeyError::Io {
            path: path.display().to_string(),
            source,
        }
    };
    let mut options = std::fs::OpenOptions::new();
    options.write(true).create_new(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt as _;
        options.mode(if private { 0o600 } else { 0o644 });
    }
    #[cfg(not(unix))]
    let _ = private;
    let mut file = options.open(path).map_err(io)?;
    file.write_all(bytes).map_err(io)?;
    file.sync_all().map_err(io)
}
